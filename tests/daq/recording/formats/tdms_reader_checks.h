#pragma once

// What the TDMS reader's tests share: the reader, a signal looked up by name, the problem a
// file's bytes raise, and a one-segment fixture with a property of every type (built byte by
// byte from NI's "TDMS File Format Internal Structure", every field commented).

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "daq/recording/format_reader.h"
#include "daq/recording/formats/formats.h"
#include "tests/daq/recording/formats/tdms_test_bytes.h"
#include "tests/daq/recording/recording_test_util.h"

namespace oscilab::daq::testing {

inline constexpr std::uint32_t kTocFirst = kTocMetaData | kTocNewObjList | kTocRawData;

inline const SignalFileReader& tdms() {
  return dynamic_cast<const SignalFileReader&>(tdms_format());
}

inline const FileSignal& signal_named(const FileContents& contents, const std::string& name) {
  for (const FileSignal& signal : contents.file_signals) {
    if (signal.name == name) return signal;
  }
  ADD_FAILURE() << "no signal " << name;
  static const FileSignal kNone;
  return kNone;
}

inline std::vector<double> read_named(const std::string& path, const std::string& name) {
  return tdms().read_signal(path, signal_named(tdms().describe(path), name), -1);
}

// The problem describing `bytes` (and reading `name` when given) raises, or "".
inline std::string error_of(const TempDir& dir, const std::string& bytes,
                            const std::string& name = "") {
  const std::string path = dir.file("bad.tdms");
  testing::write_file(path, bytes);
  return input_error_of([&] {
    const FileContents contents = tdms().describe(path);
    if (!name.empty()) tdms().read_signal(path, signal_named(contents, name), -1);
  });
}

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// One segment, little-endian, contiguous float64: the file, a group and two channels with their
// properties, and the property types TDMS defines.
inline std::string contiguous_float64_file() {
  TdmsBytes m;          // metadata, little-endian
  m.u32(4);             // 4 objects
  m.str("/");           // object 0: the file
  m.u32(kIndexNoData);  //   raw data index: none
  m.u32(13);            //   13 properties, one of each type:
  m.str("i8").u32(kTdsI8).number<std::int8_t>(-5);
  m.str("i16").u32(kTdsI16).number<std::int16_t>(-300);
  m.str("i32").u32(kTdsI32).i32(-70000);
  m.str("i64").u32(kTdsI64).number<std::int64_t>(-5000000000);
  m.str("u8").u32(kTdsU8).u8(250);
  m.str("u16").u32(kTdsU16).number<std::uint16_t>(65000);
  m.str("u32").u32(kTdsU32).u32(4000000000u);
  m.str("u64").u32(kTdsU64).u64(18446744073709551615ull);
  m.str("f32").u32(kTdsF32).number<float>(0.5f);
  m.str("title").u32(kTdsString).str("r\xC3\xBCttel run 7");  // UTF-8 "rüttel"
  m.str("ok").u32(kTdsBoolean).u8(1);
  // 2000-01-01T00:00:00.5Z: 946684800 s after 1970, 2082844800 s from 1904 to 1970; the
  // fraction 2^63 × 2^-64 s = 0.5 s. Little-endian: fraction first, then seconds.
  m.str("when").u32(kTdsTimestamp).u64(1ull << 63).number<std::int64_t>(3029529600);
  m.str("z").u32(kTdsComplex128).f64(1.5).f64(-2.0);
  m.str("/'Dr. T''s table'");  // object 1: group "Dr. T's table"
  m.u32(kIndexNoData);         //   raw data index: none
  m.u32(1);                    //   1 property
  m.str("operator").u32(kTdsString).str("A. B.");
  m.str("/'Dr. T''s table'/'base/acc'");            // object 2: channel "base/acc"
  m.u32(kIndexPlain);                               //   raw data index of 20 bytes:
  m.u32(kTdsF64);                                   //     data type float64
  m.u32(1);                                         //     array dimension 1
  m.u64(5);                                         //     5 values per chunk
  m.u32(3);                                         //   3 properties
  m.str("wf_increment").u32(kTdsF64).f64(0.002);    // s: 500 Hz
  m.str("wf_start_offset").u32(kTdsF64).f64(0.25);  // s
  m.str("unit_string").u32(kTdsString).str("m/s^2");
  m.str("/'Dr. T''s table'/'force'");  // object 3: channel "force"
  m.u32(kIndexPlain);                  //   raw data index of 20 bytes:
  m.u32(kTdsF64);                      //     data type float64
  m.u32(1);                            //     array dimension 1
  m.u64(5);                            //     5 values per chunk
  m.u32(1);                            //   1 property
  m.str("unit_string").u32(kTdsString).str("N");
  TdmsBytes raw;  // one chunk: 5 values of each channel in turn
  for (const double v : {0.0, 1.5, -2.25, 1e-300, 12345.678}) raw.f64(v);
  for (const double v : {10.0, -0.125, 3.0, 4.5, -1e10}) raw.f64(v);
  return tdms_segment(kTocFirst, m.bytes(), raw.bytes());
}

}  // namespace oscilab::daq::testing
