// The NI TDMS reader against files real instruments wrote (NI-DAQmx logging, LabVIEW
// SignalExpress) and against files built here byte by byte from NI's "TDMS File Format Internal
// Structure", every field commented.
#include <gtest/gtest.h>

#include "tests/instrument_files.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "daq/recording/format_reader.h"
#include "daq/recording/formats/formats.h"
#include "daq/recording/recording.h"
#include "tests/daq/recording/formats/tdms_test_bytes.h"
#include "tests/daq/recording/recording_test_util.h"

namespace oscilab::daq {
namespace {

using testing::channel;
using testing::input_error_of;
using testing::tdms_lead_in;
using testing::tdms_segment;
using testing::TdmsBytes;
using testing::TempDir;
using namespace testing;  // ToC flags, type codes and index headers of tdms_test_bytes.h

const std::string kFixtures = oscilab::testing::instrument_files() + "/tdms/";

constexpr std::uint32_t kTocFirst = kTocMetaData | kTocNewObjList | kTocRawData;

const SignalFileReader& tdms() { return dynamic_cast<const SignalFileReader&>(tdms_format()); }

const FileSignal& signal_named(const FileContents& contents, const std::string& name) {
  for (const FileSignal& signal : contents.file_signals) {
    if (signal.name == name) return signal;
  }
  ADD_FAILURE() << "no signal " << name;
  static const FileSignal kNone;
  return kNone;
}

std::vector<double> read_named(const std::string& path, const std::string& name) {
  return tdms().read_signal(path, signal_named(tdms().describe(path), name), -1);
}

double rms(const std::vector<double>& values) {
  double sum = 0.0;
  for (const double value : values) sum += value * value;
  return std::sqrt(sum / static_cast<double>(values.size()));
}

// The problem describing `bytes` (and reading `name` when given) raises, or "".
std::string error_of(const TempDir& dir, const std::string& bytes, const std::string& name = "") {
  const std::string path = dir.file("bad.tdms");
  testing::write_file(path, bytes);
  return input_error_of([&] {
    const FileContents contents = tdms().describe(path);
    if (!name.empty()) tdms().read_signal(path, signal_named(contents, name), -1);
  });
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// ---- Real files ------------------------------------------------------------------------------

TEST(TdmsReader, ReadsDaqmxRawInterleavedInt16WithItsLinearScales) {
  OSCILAB_SKIP_WITHOUT_INSTRUMENT_FILES();
  const std::string path = kFixtures + "example.tdms";
  const FileContents contents = tdms().describe(path);
  EXPECT_EQ(contents.container, "NI TDMS (version 4713), 4 segments");
  ASSERT_EQ(contents.file_signals.size(), 2u);
  EXPECT_EQ(contents.file_signals[0].name, "analog/NI_9775/ai0");
  EXPECT_EQ(contents.file_signals[1].name, "analog/NI_9775/ai1");
  for (const FileSignal& signal : contents.file_signals) {
    EXPECT_EQ(signal.sample_count, 4000);
    EXPECT_EQ(signal.unit, "Volts");
    EXPECT_EQ(signal.stored_type, "int16 (DAQmx raw data)");
    ASSERT_TRUE(signal.sample_rate_hz.has_value());
    EXPECT_NEAR(*signal.sample_rate_hz, 200000.0, 1e-6);  // wf_increment 5e-6 s
  }
  EXPECT_EQ(contents.file_signals[0].properties["NI_Scale[1]_Linear_Slope"], 0.001380558);
  EXPECT_EQ(contents.file_signals[1].properties["NI_Scale[1]_Linear_Slope"], 0.001371093);
  EXPECT_NEAR(contents.file_signals[0].properties["NI_Scale[1]_Linear_Y_Intercept"].get<double>(),
              -0.020247, 1e-12);
  EXPECT_EQ(contents.properties["file"]["name"], "example");
  EXPECT_TRUE(contents.properties["groups"].contains("analog"));

  const std::vector<double> ai0 = tdms().read_signal(path, contents.file_signals[0], -1);
  const std::vector<double> ai1 = tdms().read_signal(path, contents.file_signals[1], -1);
  ASSERT_EQ(ai0.size(), 4000u);
  ASSERT_EQ(ai1.size(), 4000u);
  // As measured when the file was copied: a ≈0.97 V sine of RMS 0.687 V, and ~1.5 mV of noise.
  EXPECT_NEAR(rms(ai0), 0.687, 0.0005);
  EXPECT_NEAR(*std::max_element(ai0.begin(), ai0.end()), 0.97, 0.01);
  EXPECT_NEAR(*std::min_element(ai0.begin(), ai0.end()), -0.97, 0.01);
  EXPECT_NEAR(rms(ai1), 1.5e-3, 0.1e-3);
  // Every value is slope × an int16 count + intercept.
  for (const double value : ai0) {
    const double count = (value + 0.020247) / 0.001380558;
    EXPECT_NEAR(count, std::round(count), 1e-6);
  }
}

TEST(TdmsReader, ReadsTheDigitalLineSignalExpressLoggedInNineSegments) {
  OSCILAB_SKIP_WITHOUT_INSTRUMENT_FILES();
  const std::string path = kFixtures + "Digital_Input.tdms";
  const FileContents contents = tdms().describe(path);
  EXPECT_EQ(contents.container, "NI TDMS (version 4713), 9 segments");
  const std::string all =
      "07/09/2012 06:58:23 PM - Digital Input - All Data/Dev1_port3_line7 - line 0";
  const FileSignal& line = signal_named(contents, all);
  EXPECT_EQ(line.sample_count, 20000);
  EXPECT_EQ(line.stored_type, "uint8");
  ASSERT_TRUE(line.sample_rate_hz.has_value());
  EXPECT_DOUBLE_EQ(*line.sample_rate_hz, 2000.0);  // wf_increment 0.0005 s
  EXPECT_EQ(line.properties["NI_LineNames"], "Dev1/port3/line7");
  EXPECT_EQ(contents.properties["file"]["WriterName"], "LabVIEW SignalExpress 2011");
  EXPECT_EQ(contents.properties["file"]["recording-complete"], true);
  EXPECT_EQ(contents.properties["file"]["DateTime"].get<std::string>().substr(0, 4), "2012");

  const std::vector<double> values = tdms().read_signal(path, line, -1);
  ASSERT_EQ(values.size(), 20000u);
  for (const double value : values) EXPECT_TRUE(value == 0.0 || value == 1.0) << value;
  // The decimated copy as npTDMS's own test reads it: 0, 1, 0, 1, ...
  const std::vector<double> decimated = read_named(
      path,
      "07/09/2012 06:58:23 PM - Digital Input - Decimated Data_Level1/Dev1_port3_line7 - "
      "line 0");
  ASSERT_EQ(decimated.size(), 400u);
  for (std::size_t i = 0; i < 10; ++i) EXPECT_EQ(decimated[i], static_cast<double>(i % 2));
}

TEST(TdmsReader, MapsTheRealDaqmxFileThroughASidecar) {
  OSCILAB_SKIP_WITHOUT_INSTRUMENT_FILES();
  Sidecar sidecar;
  sidecar.sample_rate_hz = 200000.0;
  sidecar.channels = {channel("v0", ChannelRole::Base, Quantity::Acceleration, "V", 2.0),
                      channel("v1", ChannelRole::Mass, Quantity::Acceleration, "V", 1.0)};
  sidecar.channels[0].source = "analog/NI_9775/ai0";
  sidecar.channels[1].source = "analog/NI_9775/ai1";
  const Recording recording = read_recording(kFixtures + "example.tdms", sidecar);
  ASSERT_EQ(recording.sample_count(), 4000);
  EXPECT_EQ(recording.container, "NI TDMS (version 4713), 4 segments");
  const std::vector<double> ai0 = read_named(kFixtures + "example.tdms", "analog/NI_9775/ai0");
  for (Eigen::Index r = 0; r < 4000; ++r) {
    EXPECT_EQ(recording.samples_stored(r, 0), ai0[static_cast<std::size_t>(r)]);
    EXPECT_EQ(recording.samples_si(r, 0), 2.0 * ai0[static_cast<std::size_t>(r)]);  // scale 2
  }
}

// ---- Byte-level fixtures ---------------------------------------------------------------------

// One segment, little-endian, contiguous float64: the file, a group and two channels with their
// properties, and the property types TDMS defines.
std::string contiguous_float64_file() {
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

TEST(TdmsReader, ReadsContiguousFloat64WithPropertiesOfEveryType) {
  const TempDir dir;
  const std::string path = dir.file("run.tdms");
  testing::write_file(path, contiguous_float64_file());
  EXPECT_EQ(&format_for_file(path), &tdms_format());
  const FileContents contents = tdms().describe(path);
  EXPECT_EQ(contents.container, "NI TDMS (version 4713), 1 segment");
  ASSERT_EQ(contents.file_signals.size(), 2u);
  const FileSignal& base = contents.file_signals[0];
  EXPECT_EQ(base.name, "Dr. T's table/base/acc");
  EXPECT_EQ(base.sample_count, 5);
  EXPECT_EQ(base.unit, "m/s^2");
  EXPECT_EQ(base.stored_type, "float64");
  ASSERT_TRUE(base.sample_rate_hz.has_value());
  EXPECT_DOUBLE_EQ(*base.sample_rate_hz, 500.0);
  EXPECT_EQ(base.properties["wf_start_offset"], 0.25);
  EXPECT_EQ(contents.file_signals[1].name, "Dr. T's table/force");
  EXPECT_EQ(contents.file_signals[1].unit, "N");
  EXPECT_FALSE(contents.file_signals[1].sample_rate_hz.has_value());
  EXPECT_EQ(contents.properties["groups"]["Dr. T's table"]["operator"], "A. B.");

  const nlohmann::json& file = contents.properties["file"];
  EXPECT_EQ(file["i8"], -5);
  EXPECT_EQ(file["i16"], -300);
  EXPECT_EQ(file["i32"], -70000);
  EXPECT_EQ(file["i64"], -5000000000);
  EXPECT_EQ(file["u8"], 250);
  EXPECT_EQ(file["u16"], 65000);
  EXPECT_EQ(file["u32"], 4000000000u);
  EXPECT_EQ(file["u64"], 18446744073709551615ull);
  EXPECT_EQ(file["f32"], 0.5);
  EXPECT_EQ(file["title"], "r\xC3\xBCttel run 7");
  EXPECT_EQ(file["ok"], true);
  EXPECT_EQ(file["when"], "2000-01-01T00:00:00.500000Z");
  EXPECT_EQ(file["z"], nlohmann::json::array({1.5, -2.0}));
  EXPECT_NO_THROW((void)contents.properties.dump());

  EXPECT_EQ(tdms().read_signal(path, base, -1),
            (std::vector<double>{0.0, 1.5, -2.25, 1e-300, 12345.678}));
  EXPECT_EQ(tdms().read_signal(path, contents.file_signals[1], -1),
            (std::vector<double>{10.0, -0.125, 3.0, 4.5, -1e10}));
}

TEST(TdmsReader, ReadsInterleavedInt32BigEndian) {
  const std::uint32_t toc = kTocFirst | kTocInterleavedData | kTocBigEndian;
  TdmsBytes m(true);    // metadata, big-endian
  m.u32(3);             // 3 objects
  m.str("/'g'");        // object 0: group "g"
  m.u32(kIndexNoData);  //   no raw data
  m.u32(1);             //   1 property: a timestamp, big-endian: seconds first
  m.str("t0").u32(kTdsTimestamp).number<std::int64_t>(3029529600).u64(1ull << 62);  // +0.25 s
  for (const char* name : {"/'g'/'a'", "/'g'/'b'"}) {
    m.str(name);         // object: a channel
    m.u32(kIndexPlain);  //   raw data index of 20 bytes:
    m.u32(kTdsI32);      //     int32
    m.u32(1);            //     array dimension 1
    m.u64(4);            //     4 values per chunk
    m.u32(0);            //   no properties
  }
  TdmsBytes raw(true);  // rows of (a, b), big-endian
  const std::int32_t a[] = {1, -2, 2147483647, -2147483647 - 1};
  const std::int32_t b[] = {100000, 0, -7, 65536};
  for (int r = 0; r < 4; ++r) raw.i32(a[r]).i32(b[r]);
  const TempDir dir;
  const std::string path = dir.file("be.tdms");
  testing::write_file(path, tdms_segment(toc, m.bytes(), raw.bytes()));
  const FileContents contents = tdms().describe(path);
  EXPECT_EQ(contents.properties["groups"]["g"]["t0"], "2000-01-01T00:00:00.250000Z");
  EXPECT_EQ(read_named(path, "g/a"), (std::vector<double>{1, -2, 2147483647, -2147483648.0}));
  EXPECT_EQ(read_named(path, "g/b"), (std::vector<double>{100000, 0, -7, 65536}));
}

// A channel's plain raw data index: 20 bytes.
void plain_index(TdmsBytes& m, std::uint32_t type, std::uint64_t values) {
  m.u32(kIndexPlain);  // raw data index of 20 bytes
  m.u32(type);         // data type
  m.u32(1);            // array dimension 1
  m.u64(values);       // values per chunk
}

TEST(TdmsReader, ReusesTheRawDataIndexOfThePreviousSegment) {
  TdmsBytes m0;                 // segment 0: new object list
  m0.u32(2);                    // 2 objects
  m0.str("/'g'/'a'");           // channel a:
  plain_index(m0, kTdsI16, 3);  //   int16, 3 values per chunk
  m0.u32(0);                    //   no properties
  m0.str("/'g'/'b'");           // channel b:
  plain_index(m0, kTdsF32, 3);  //   float32, 3 values per chunk
  m0.u32(0);                    //   no properties
  TdmsBytes r0;
  r0.number<std::int16_t>(1).number<std::int16_t>(2).number<std::int16_t>(3);
  r0.number<float>(0.5f).number<float>(1.5f).number<float>(2.5f);

  TdmsBytes m1;                  // segment 1: metadata, same object list
  m1.u32(2);                     // 2 objects
  m1.str("/'g'/'a'");            // channel a:
  m1.u32(kIndexSameAsPrevious);  //   raw data index as in the previous segment
  m1.u32(0);                     //   no properties
  m1.str("/'g'/'b'");            // channel b:
  m1.u32(kIndexSameAsPrevious);  //   raw data index as in the previous segment
  m1.u32(0);                     //   no properties
  TdmsBytes r1;
  r1.number<std::int16_t>(4).number<std::int16_t>(5).number<std::int16_t>(6);
  r1.number<float>(3.5f).number<float>(4.5f).number<float>(5.5f);

  TdmsBytes r2;  // segment 2: no metadata at all, raw data only
  r2.number<std::int16_t>(-7).number<std::int16_t>(-8).number<std::int16_t>(-9);
  r2.number<float>(-1.0f).number<float>(-2.0f).number<float>(-3.0f);

  const TempDir dir;
  const std::string path = dir.file("reuse.tdms");
  testing::write_file(path, tdms_segment(kTocFirst, m0.bytes(), r0.bytes()) +
                                tdms_segment(kTocMetaData | kTocRawData, m1.bytes(), r1.bytes()) +
                                tdms_segment(kTocRawData, "", r2.bytes()));
  EXPECT_EQ(tdms().describe(path).container, "NI TDMS (version 4713), 3 segments");
  EXPECT_EQ(read_named(path, "g/a"), (std::vector<double>{1, 2, 3, 4, 5, 6, -7, -8, -9}));
  EXPECT_EQ(read_named(path, "g/b"),
            (std::vector<double>{0.5, 1.5, 2.5, 3.5, 4.5, 5.5, -1.0, -2.0, -3.0}));
}

TEST(TdmsReader, FollowsObjectsAddedAndChangedAcrossSegments) {
  TdmsBytes m0;                 // segment 0: new object list [a]
  m0.u32(1);                    // 1 object
  m0.str("/'g'/'a'");           // channel a:
  plain_index(m0, kTdsF64, 2);  //   float64, 2 values per chunk
  m0.u32(1);                    //   1 property
  m0.str("unit_string").u32(kTdsString).str("V");
  TdmsBytes r0;
  r0.f64(1.0).f64(2.0);

  TdmsBytes m1;                 // segment 1: no new object list: b is appended → [a, b]
  m1.u32(1);                    // 1 object
  m1.str("/'g'/'b'");           // channel b:
  plain_index(m1, kTdsF64, 3);  //   float64, 3 values per chunk
  m1.u32(0);                    //   no properties
  TdmsBytes r1;
  r1.f64(3.0).f64(4.0);              // a, as before
  r1.f64(10.0).f64(11.0).f64(12.0);  // b

  TdmsBytes m2;                  // segment 2: new object list [b]
  m2.u32(1);                     // 1 object
  m2.str("/'g'/'b'");            // channel b:
  m2.u32(kIndexSameAsPrevious);  //   as before: 3 values
  m2.u32(0);                     //   no properties
  TdmsBytes r2;
  r2.f64(13.0).f64(14.0).f64(15.0);

  TdmsBytes m3;                 // segment 3: b changes its index, a comes back without data
  m3.u32(2);                    // 2 objects
  m3.str("/'g'/'b'");           // channel b:
  plain_index(m3, kTdsF64, 1);  //   float64, now 1 value per chunk
  m3.u32(0);                    //   no properties
  m3.str("/'g'/'a'");           // channel a:
  m3.u32(kIndexNoData);         //   no data in this segment
  m3.u32(1);                    //   1 property, changed
  m3.str("unit_string").u32(kTdsString).str("mV");
  TdmsBytes r3;
  r3.f64(16.0);

  const TempDir dir;
  const std::string path = dir.file("incremental.tdms");
  testing::write_file(path, tdms_segment(kTocFirst, m0.bytes(), r0.bytes()) +
                                tdms_segment(kTocMetaData | kTocRawData, m1.bytes(), r1.bytes()) +
                                tdms_segment(kTocFirst, m2.bytes(), r2.bytes()) +
                                tdms_segment(kTocMetaData | kTocRawData, m3.bytes(), r3.bytes()));
  const FileContents contents = tdms().describe(path);
  EXPECT_EQ(signal_named(contents, "g/a").sample_count, 4);
  EXPECT_EQ(signal_named(contents, "g/a").unit, "mV");  // the last value given
  EXPECT_EQ(signal_named(contents, "g/b").sample_count, 7);
  EXPECT_EQ(read_named(path, "g/a"), (std::vector<double>{1, 2, 3, 4}));
  EXPECT_EQ(read_named(path, "g/b"), (std::vector<double>{10, 11, 12, 13, 14, 15, 16}));
}

TEST(TdmsReader, ReadsEveryChunkOfASegment) {
  TdmsBytes m;
  m.u32(2);                    // 2 objects
  m.str("/'g'/'a'");           // channel a:
  plain_index(m, kTdsU16, 2);  //   uint16, 2 values per chunk
  m.u32(0);                    //   no properties
  m.str("/'g'/'b'");           // channel b:
  plain_index(m, kTdsI8, 1);   //   int8, 1 value per chunk
  m.u32(0);                    //   no properties
  TdmsBytes raw;               // 3 chunks of 5 bytes: a, a, b
  raw.number<std::uint16_t>(1).number<std::uint16_t>(2).number<std::int8_t>(-1);
  raw.number<std::uint16_t>(3).number<std::uint16_t>(4).number<std::int8_t>(-2);
  raw.number<std::uint16_t>(65535).number<std::uint16_t>(6).number<std::int8_t>(-128);
  const TempDir dir;
  const std::string path = dir.file("chunks.tdms");
  testing::write_file(path, tdms_segment(kTocFirst, m.bytes(), raw.bytes()));
  EXPECT_EQ(read_named(path, "g/a"), (std::vector<double>{1, 2, 3, 4, 65535, 6}));
  EXPECT_EQ(read_named(path, "g/b"), (std::vector<double>{-1, -2, -128}));
}

// Two float64 channels of 2 values per chunk (32-byte chunks), `chunks` whole chunks and
// `partial` bytes more, behind a lead-in whose next-segment offset is `next`.
std::string file_being_written(std::uint64_t next, int chunks, int partial) {
  TdmsBytes m;
  m.u32(2);                    // 2 objects
  m.str("/'g'/'a'");           // channel a:
  plain_index(m, kTdsF64, 2);  //   float64, 2 values per chunk
  m.u32(0);                    //   no properties
  m.str("/'g'/'b'");           // channel b:
  plain_index(m, kTdsF64, 2);  //   float64, 2 values per chunk
  m.u32(0);                    //   no properties
  TdmsBytes raw;
  for (int c = 0; c < chunks; ++c) raw.f64(c).f64(c + 0.5).f64(-c).f64(-c - 0.5);
  std::string bytes = raw.bytes() + std::string(static_cast<std::size_t>(partial), '\x7f');
  return tdms_lead_in(kTocFirst, 4713, next, m.size()) + m.bytes() + bytes;
}

TEST(TdmsReader, ReadsTheWholeChunksOfASegmentStillBeingWrittenAndSaysWhatIsLeftOut) {
  const TempDir dir;
  const std::string path = dir.file("live.tdms");
  testing::write_file(path, file_being_written(0xFFFFFFFFFFFFFFFFull, 2, 20));
  const FileContents contents = tdms().describe(path);
  EXPECT_EQ(contents.container,
            "NI TDMS (version 4713), 1 segment; segment 0 is cut short (its length was never "
            "written, a file still being written?): its 2 whole chunks are read, 20 bytes of a "
            "partial chunk are left out");
  EXPECT_EQ(contents.properties["truncation"].get<std::string>().substr(0, 9), "segment 0");
  EXPECT_EQ(read_named(path, "g/a"), (std::vector<double>{0, 0.5, 1, 1.5}));
  EXPECT_EQ(read_named(path, "g/b"), (std::vector<double>{-0.0, -0.5, -1, -1.5}));

  // A next-segment offset beyond the end of the file: 5 chunks announced, 2 written.
  const std::string announced = file_being_written(0, 2, 0);
  const std::uint64_t metadata_bytes = announced.size() - 28 - 64;
  testing::write_file(path, file_being_written(metadata_bytes + 5 * 32, 2, 0));
  EXPECT_TRUE(contains(tdms().describe(path).container,
                       "segment 0 is cut short (it should end 96 bytes after the end of the file, "
                       "a file still being written?): its 2 whole chunks are read, 0 bytes of a "
                       "partial chunk are left out"))
      << tdms().describe(path).container;
  EXPECT_EQ(read_named(path, "g/a"), (std::vector<double>{0, 0.5, 1, 1.5}));

  // The first bytes of a next lead-in.
  testing::write_file(path, contiguous_float64_file() + "TDSm\x0e");
  EXPECT_TRUE(contains(tdms().describe(path).container,
                       "the file ends 5 bytes into the lead-in of segment 1"));
  EXPECT_EQ(read_named(path, "Dr. T's table/force").size(), 5u);
}

TEST(TdmsReader, ReadsDaqmxFormatChangingScalersThroughAChainOfLinearScales) {
  const std::uint32_t toc = kTocFirst | kTocInterleavedData | kTocDAQmxRawData;
  TdmsBytes m;
  m.u32(2);  // 2 objects
  for (int c = 0; c < 2; ++c) {
    m.str(c == 0 ? "/'daq'/'x'" : "/'daq'/'y'");  // a channel:
    m.u32(kIndexFormatChangingScaler);            //   DAQmx raw data index, format-changing scaler
    m.u32(kTdsDaqmxRaw);                          //     data type: DAQmx raw data
    m.u32(1);                                     //     array dimension 1
    m.u64(3);                                     //     3 values per chunk
    m.u32(1);                                     //     1 scaler:
    m.u32(3);                                     //       DAQmx data type 3: int16
    m.u32(0);                                     //       raw buffer 0
    m.u32(c == 0 ? 0 : 2);                        //       byte offset in the stride
    m.u32(0);                                     //       sample format bitmap
    m.u32(0);                                     //       scale ID 0
    m.u32(1);                                     //     1 raw data width:
    m.u32(4);                                     //       4 bytes per stride
    m.u32(c == 0 ? 7 : 10);                       //   properties:
    m.str("NI_Scaling_Status").u32(kTdsString).str("unscaled");
    if (c == 0) {  // x = 0.5 × raw − 1
      m.str("NI_Number_Of_Scales").u32(kTdsU32).u32(2);
      m.str("NI_Scale[1]_Scale_Type").u32(kTdsString).str("Linear");
      m.str("NI_Scale[1]_Linear_Slope").u32(kTdsF64).f64(0.5);
      m.str("NI_Scale[1]_Linear_Y_Intercept").u32(kTdsF64).f64(-1.0);
      m.str("NI_Scale[1]_Linear_Input_Source").u32(kTdsU32).u32(0);
    } else {  // y = 4 × (2 × raw + 0.25) − 3
      m.str("NI_Number_Of_Scales").u32(kTdsU32).u32(3);
      m.str("NI_Scale[1]_Scale_Type").u32(kTdsString).str("Linear");
      m.str("NI_Scale[1]_Linear_Slope").u32(kTdsF64).f64(2.0);
      m.str("NI_Scale[1]_Linear_Y_Intercept").u32(kTdsF64).f64(0.25);
      m.str("NI_Scale[1]_Linear_Input_Source").u32(kTdsU32).u32(0);
      m.str("NI_Scale[2]_Scale_Type").u32(kTdsString).str("Linear");
      m.str("NI_Scale[2]_Linear_Slope").u32(kTdsF64).f64(4.0);
      m.str("NI_Scale[2]_Linear_Y_Intercept").u32(kTdsF64).f64(-3.0);
      m.str("NI_Scale[2]_Linear_Input_Source").u32(kTdsU32).u32(1);
    }
    m.str("unit_string").u32(kTdsString).str("V");
  }
  TdmsBytes raw;  // 3 strides of (x, y), int16
  const std::int16_t x[] = {10, -32768, 7};
  const std::int16_t y[] = {-4, 0, 32767};
  for (int r = 0; r < 3; ++r) raw.number(x[r]).number(y[r]);
  const TempDir dir;
  const std::string path = dir.file("daqmx.tdms");
  testing::write_file(path, tdms_segment(toc, m.bytes(), raw.bytes() + raw.bytes()));  // 2 chunks
  EXPECT_EQ(signal_named(tdms().describe(path), "daq/x").stored_type, "int16 (DAQmx raw data)");
  EXPECT_EQ(read_named(path, "daq/x"),
            (std::vector<double>{4.0, -16385.0, 2.5, 4.0, -16385.0, 2.5}));
  const std::vector<double> y_expected = {-34.0, -2.0, 262134.0};
  EXPECT_EQ(read_named(path, "daq/y"),
            (std::vector<double>{y_expected[0], y_expected[1], y_expected[2], y_expected[0],
                                 y_expected[1], y_expected[2]}));
}

TEST(TdmsReader, ReadsADaqmxDigitalLine) {
  const std::uint32_t toc = kTocFirst | kTocInterleavedData | kTocDAQmxRawData;
  TdmsBytes m;
  m.u32(1);                        // 1 object
  m.str("/'dio'/'line 10'");       // a channel:
  m.u32(kIndexDigitalLineScaler);  //   DAQmx raw data index, digital line scaler
  m.u32(kTdsDaqmxRaw);             //     data type: DAQmx raw data
  m.u32(1);                        //     array dimension 1
  m.u64(4);                        //     4 values per chunk
  m.u32(1);                        //     1 scaler:
  m.u32(0);                        //       DAQmx data type 0: uint8
  m.u32(0);                        //       raw buffer 0
  m.u32(10);                       //       bit 10 of the stride: byte 1, bit 2
  m.u8(0);                         //       sample format bitmap (1 byte here)
  m.u32(0);                        //       scale ID 0
  m.u32(1);                        //     1 raw data width:
  m.u32(2);                        //       2 bytes per stride
  m.u32(0);                        //   no properties
  const std::string raw(
      "\xff\x04"
      "\xff\xfb"
      "\x00\x07"
      "\x00\x00",
      8);  // bit 2 of byte 1
  const TempDir dir;
  const std::string path = dir.file("dio.tdms");
  testing::write_file(path, tdms_segment(toc, m.bytes(), raw));
  EXPECT_EQ(signal_named(tdms().describe(path), "dio/line 10").stored_type,
            "uint8 (DAQmx digital line)");
  EXPECT_EQ(read_named(path, "dio/line 10"), (std::vector<double>{1, 0, 1, 0}));
}

// The same stored values in a TDMS file and in a CSV (and int16 counts in a 16-bit WAV) reach the
// same recording, bit for bit.
TEST(TdmsReader, ReachesTheSameRecordingAsCsvAndWavHoldingTheSameValues) {
  const int kRows = 257;
  std::vector<double> base(kRows), force(kRows);
  std::vector<std::int16_t> counts(2 * kRows);
  for (int r = 0; r < kRows; ++r) {
    base[r] = std::sin(0.37 * r) * 3.1 + 1e-9 * r;
    force[r] = std::cos(0.11 * r) / 7.0;
    counts[2 * r] = static_cast<std::int16_t>(std::lround(30000 * std::sin(0.05 * r)));
    counts[2 * r + 1] = static_cast<std::int16_t>(r * 100 - 12000);
  }
  TdmsBytes m;
  m.u32(4);                // 4 objects
  m.str("/'rig'/'base'");  // float64 channel "base", 257 values
  plain_index(m, kTdsF64, kRows);
  m.u32(0);
  m.str("/'rig'/'force'");  // float64 channel "force", 257 values
  plain_index(m, kTdsF64, kRows);
  m.u32(0);
  m.str("/'rig'/'c0'");  // int16 channel "c0", 257 values
  plain_index(m, kTdsI16, kRows);
  m.u32(0);
  m.str("/'rig'/'c1'");  // int16 channel "c1", 257 values
  plain_index(m, kTdsI16, kRows);
  m.u32(0);
  TdmsBytes raw;
  for (const double v : base) raw.f64(v);
  for (const double v : force) raw.f64(v);
  for (int r = 0; r < kRows; ++r) raw.number(counts[2 * r]);
  for (int r = 0; r < kRows; ++r) raw.number(counts[2 * r + 1]);
  const TempDir dir;
  testing::write_file(dir.file("rec.tdms"), tdms_segment(kTocFirst, m.bytes(), raw.bytes()));

  std::string csv = "base,force\n";
  for (int r = 0; r < kRows; ++r) {
    char text[64];
    csv += std::string(text, std::to_chars(text, text + sizeof text, base[r]).ptr) + ",";
    csv += std::string(text, std::to_chars(text, text + sizeof text, force[r]).ptr) + "\n";
  }
  testing::write_file(dir.file("rec.csv"), csv);
  testing::write_file(dir.file("rec.wav"), testing::pcm16_wav(512, 2, counts));

  Sidecar sidecar;
  sidecar.sample_rate_hz = 512.0;
  sidecar.channels = {channel("base", ChannelRole::Base, Quantity::Acceleration, "g", 0.5, 0.1),
                      channel("force", ChannelRole::Force, Quantity::Force, "N", 20.0)};
  const Recording from_csv = read_recording(dir.file("rec.csv"), sidecar);
  sidecar.channels[0].source = "rig/base";
  sidecar.channels[1].source = "rig/force";
  const Recording from_tdms = read_recording(dir.file("rec.tdms"), sidecar);
  ASSERT_EQ(from_tdms.sample_count(), kRows);
  EXPECT_TRUE((from_tdms.samples_si.array() == from_csv.samples_si.array()).all());
  EXPECT_TRUE((from_tdms.samples_stored.array() == from_csv.samples_stored.array()).all());

  sidecar.channels[0].source = "rig/c0";
  sidecar.channels[1].source = "rig/c1";
  const Recording from_wav = read_recording(dir.file("rec.wav"), sidecar);
  const Recording from_counts = read_recording(dir.file("rec.tdms"), sidecar);
  ASSERT_EQ(from_counts.sample_count(), kRows);
  EXPECT_TRUE((from_counts.samples_si.array() == from_wav.samples_si.array()).all());
  EXPECT_EQ(from_counts.samples_stored(1, 1), -11900.0);
}

// ---- Refusals --------------------------------------------------------------------------------

// One segment with one float64 channel "g/c" of 2 values, `index` replacing its raw data index.
std::string one_channel_file(const std::string& index, std::uint32_t toc = kTocFirst,
                             const std::string& raw = std::string(16, '\0')) {
  TdmsBytes m;
  m.u32(1);           // 1 object
  m.str("/'g'/'c'");  // channel c of group g
  m.raw(index);       //   its raw data index
  m.u32(0);           //   no properties
  return tdms_segment(toc, m.bytes(), raw);
}

std::string plain_index_bytes(std::uint32_t type, std::uint64_t values, std::uint32_t dimension = 1,
                              std::uint32_t length = kIndexPlain) {
  TdmsBytes index;
  index.u32(length).u32(type).u32(dimension).u64(values);
  return index.bytes();
}

TEST(TdmsReader, RefusesFilesThatAreNotTdms) {
  const TempDir dir;
  std::string bytes = one_channel_file(plain_index_bytes(kTdsF64, 2));
  bytes[3] = 'h';  // "TDSh": an index file
  EXPECT_EQ(error_of(dir, bytes), dir.file("bad.tdms") +
                                      ": segment 0 at byte 0: not a TDMS file: it starts with "
                                      "\"TDSh\", not \"TDSm\"");
  EXPECT_TRUE(contains(error_of(dir, one_channel_file(plain_index_bytes(kTdsF64, 2)) + "junk!"),
                       "segment 1 at byte 84: not a TDMS segment: it starts with \"junk\""));
  EXPECT_EQ(error_of(dir, ""), dir.file("bad.tdms") + ": not a TDMS file: the file is empty");
}

TEST(TdmsReader, RefusesAnUnknownVersion) {
  const TempDir dir;
  const std::string bytes = tdms_lead_in(kTocRawData, 4714, 0, 0);
  EXPECT_EQ(error_of(dir, bytes), dir.file("bad.tdms") +
                                      ": segment 0 at byte 0: unknown version 4714 (4712 and "
                                      "4713 are read)");
  EXPECT_EQ(error_of(dir, tdms_lead_in(kTocRawData, 4712, 0, 0)), "");
}

TEST(TdmsReader, RefusesOffsetsThatPointBeyondTheFileOrBackwards) {
  const TempDir dir;
  EXPECT_EQ(error_of(dir, tdms_lead_in(kTocFirst, 4713, 100, 50) + std::string(10, '\0')),
            dir.file("bad.tdms") +
                ": segment 0 at byte 0: the raw data offset 50 points beyond the end of the file "
                "(10 bytes follow the lead-in)");
  EXPECT_TRUE(contains(error_of(dir, tdms_lead_in(kTocFirst, 4713, 4, 8) + std::string(10, '\0')),
                       "the next segment offset 4 lies before the raw data offset 8"));
  // An object's raw data index longer than the metadata left.
  EXPECT_TRUE(contains(error_of(dir, one_channel_file(plain_index_bytes(kTdsF64, 2, 1, 200))),
                       "object 0 \"/'g'/'c'\": its raw data index of 200 bytes points beyond the "
                       "end of the metadata"));
  // A string length beyond the metadata.
  TdmsBytes m;
  m.u32(1).u32(1000).raw("/'g'");
  EXPECT_TRUE(contains(error_of(dir, tdms_segment(kTocFirst, m.bytes(), "")),
                       "object 0: an object path at byte 36 needs 1000 bytes, the metadata has 4 "
                       "left"));
}

TEST(TdmsReader, RefusesUnknownAndUnreadDataTypes) {
  const TempDir dir;
  EXPECT_TRUE(contains(error_of(dir, one_channel_file(plain_index_bytes(0x77, 2))),
                       "object 0 \"/'g'/'c'\": unknown data type 0x77"));
  EXPECT_TRUE(contains(error_of(dir, one_channel_file(plain_index_bytes(kTdsFixedPoint, 2))),
                       "data type fixed-point (0x4F) is not read (its size in the raw data is not "
                       "documented)"));
  EXPECT_TRUE(contains(error_of(dir, one_channel_file(plain_index_bytes(0x0B, 2))),
                       "data type extended float (0xB) is not read"));
  TdmsBytes m;
  m.u32(1).str("/").u32(kIndexNoData).u32(1).str("q").u32(kTdsFixedPoint);
  EXPECT_TRUE(contains(error_of(dir, tdms_segment(kTocFirst, m.bytes(), "")),
                       "object 0 \"/\": property \"q\": data type fixed-point (0x4F) is not read"));
  // Readable layouts whose values are not samples: listed, refused when read.
  EXPECT_EQ(error_of(dir,
                     one_channel_file(plain_index_bytes(kTdsComplex128, 1), kTocFirst,
                                      std::string(16, '\0')),
                     "g/c"),
            dir.file("bad.tdms") +
                ": \"g/c\" stores complex128 values, which are not samples "
                "(int8 to uint64, float32 and float64 are read)");
  TdmsBytes strings;  // 2 strings "ab", "c": end offsets 2 and 3, then the text
  strings.u32(kIndexPlainStrings).u32(kTdsString).u32(1).u64(2).u64(11);
  TdmsBytes text;
  text.u32(2).u32(3).raw("abc");
  EXPECT_TRUE(
      contains(error_of(dir, one_channel_file(strings.bytes(), kTocFirst, text.bytes()), "g/c"),
               "\"g/c\" stores string values, which are not samples"));
  EXPECT_TRUE(contains(error_of(dir,
                                one_channel_file(plain_index_bytes(kTdsTimestamp, 1), kTocFirst,
                                                 std::string(16, '\0')),
                                "g/c"),
                       "stores timestamp values"));
}

TEST(TdmsReader, RefusesInconsistentRawDataIndexes) {
  const TempDir dir;
  EXPECT_TRUE(contains(error_of(dir, one_channel_file(plain_index_bytes(kTdsF64, 2, 2))),
                       "array dimension 2 (only 1 is defined)"));
  EXPECT_TRUE(contains(error_of(dir, one_channel_file(plain_index_bytes(kTdsF64, 2, 1, 12))),
                       "raw data index length 12 (20, or 28 for strings)"));
  EXPECT_TRUE(contains(error_of(dir, one_channel_file(plain_index_bytes(kTdsF64, 1ull << 62))),
                       "it declares 4611686018427387904 values of float64 per chunk, more than "
                       "the file holds"));
  EXPECT_TRUE(contains(error_of(dir, one_channel_file(plain_index_bytes(kTdsString, 2))),
                       "a raw data index of strings needs 28 bytes, not 20"));
  TdmsBytes strings;
  strings.u32(kIndexPlainStrings).u32(kTdsString).u32(1).u64(5).u64(16);
  EXPECT_TRUE(contains(error_of(dir, one_channel_file(strings.bytes())),
                       "strings of 16 bytes for 5 values do not fit the file"));
  TdmsBytes same;
  same.u32(kIndexSameAsPrevious);
  EXPECT_TRUE(contains(error_of(dir, one_channel_file(same.bytes())),
                       "its raw data index says \"same as the previous segment\", but no earlier "
                       "segment gave one"));
  // 16 bytes of data for 3-value chunks of float64 (24 bytes).
  EXPECT_TRUE(contains(error_of(dir, one_channel_file(plain_index_bytes(kTdsF64, 3))),
                       "its 16 bytes of raw data are not a whole number of 24-byte chunks"));
  EXPECT_TRUE(contains(error_of(dir, one_channel_file(plain_index_bytes(kTdsF64, 2), kTocFirst,
                                                      std::string(16, '\0')) +
                                         one_channel_file(plain_index_bytes(kTdsI32, 4))),
                       "segment 1 at byte 84: object 0 \"/'g'/'c'\": its data type changes from "
                       "float64 (0xA) to int32 (0x3)"));
  // Raw data where no channel has any.
  TdmsBytes none;
  none.u32(kIndexNoData);
  EXPECT_TRUE(contains(error_of(dir, one_channel_file(none.bytes())),
                       "it holds 16 bytes of raw data, but no channel has data in it"));
  // A raw data index on a group.
  TdmsBytes m;
  m.u32(1).str("/'g'").raw(plain_index_bytes(kTdsF64, 2)).u32(0);
  EXPECT_TRUE(contains(error_of(dir, tdms_segment(kTocFirst, m.bytes(), std::string(16, '\0'))),
                       "object 0 \"/'g'\": only channels hold raw data"));
  // Two channels whose chunks together outgrow the file.
  TdmsBytes big;
  big.u32(2);
  big.str("/'g'/'a'").raw(plain_index_bytes(kTdsU8, 60)).u32(0);
  big.str("/'g'/'b'").raw(plain_index_bytes(kTdsU8, 60)).u32(0);
  EXPECT_TRUE(contains(error_of(dir, tdms_segment(kTocFirst, big.bytes(), std::string(4, '\0'))),
                       "bytes or more are larger than the file"));
}

TEST(TdmsReader, RefusesMalformedObjectPaths) {
  const TempDir dir;
  for (const std::string path : {"g/c", "/'g", "/'g'/", "/'a'/'b'/'c'", "/'g'x"}) {
    TdmsBytes m;
    m.u32(1).str(path).u32(kIndexNoData).u32(0);
    const std::string message = error_of(dir, tdms_segment(kTocFirst, m.bytes(), ""));
    EXPECT_TRUE(contains(message, "not an object path (/, /'group' or /'group'/'channel')"))
        << path << ": " << message;
  }
}

TEST(TdmsReader, RefusesInterleavedChannelsOfDifferentLengthsOrOfStrings) {
  const TempDir dir;
  TdmsBytes m;
  m.u32(2);
  m.str("/'g'/'a'").raw(plain_index_bytes(kTdsF64, 2)).u32(0);
  m.str("/'g'/'b'").raw(plain_index_bytes(kTdsF64, 3)).u32(0);
  EXPECT_TRUE(contains(
      error_of(dir, tdms_segment(kTocFirst | kTocInterleavedData, m.bytes(), std::string(40, 0))),
      "channel \"/'g'/'b'\": interleaved with 3 values per chunk, another channel has 2"));
  TdmsBytes s;
  s.u32(1).str("/'g'/'s'");
  s.u32(kIndexPlainStrings).u32(kTdsString).u32(1).u64(1).u64(5).u32(0);
  EXPECT_TRUE(contains(
      error_of(dir, tdms_segment(kTocFirst | kTocInterleavedData, s.bytes(), std::string(5, 0))),
      "channel \"/'g'/'s'\": interleaved strings"));
  TdmsBytes wide;
  wide.u32(2);
  wide.str("/'g'/'a'").raw(plain_index_bytes(kTdsU8, 13)).u32(0);
  wide.str("/'g'/'b'").raw(plain_index_bytes(kTdsF64, 13)).u32(0);
  EXPECT_TRUE(contains(
      error_of(dir, tdms_segment(kTocFirst | kTocInterleavedData, wide.bytes(), std::string(9, 0))),
      "its interleaved rows of 9 bytes are more than the file holds"));
}

// A DAQmx raw data index with one format-changing scaler (`type`, `buffer`, `offset`, scale ID
// `scale_id`) and the raw buffer widths `widths`.
std::string daqmx_index(std::uint64_t values, std::uint32_t type, std::uint32_t buffer,
                        std::uint32_t offset, std::vector<std::uint32_t> widths,
                        std::uint32_t scale_id = 0, std::uint32_t scalers = 1) {
  TdmsBytes index;
  index.u32(kIndexFormatChangingScaler);  // DAQmx, format-changing scaler
  index.u32(kTdsDaqmxRaw);                // data type: DAQmx raw data
  index.u32(1);                           // array dimension 1
  index.u64(values);                      // values per chunk
  index.u32(scalers);                     // number of scalers
  for (std::uint32_t s = 0; s < std::min<std::uint32_t>(scalers, 4); ++s) {
    index.u32(type);            //   DAQmx data type
    index.u32(buffer);          //   raw buffer
    index.u32(offset + 2 * s);  //   byte offset in the stride
    index.u32(0);               //   sample format bitmap
    index.u32(scale_id + s);    //   scale ID
  }
  index.u32(static_cast<std::uint32_t>(widths.size()));  // number of raw data widths
  for (const std::uint32_t width : widths) index.u32(width);
  return index.bytes();
}

constexpr std::uint32_t kTocDaqmx = kTocFirst | kTocInterleavedData | kTocDAQmxRawData;

TEST(TdmsReader, RefusesInconsistentDaqmxIndexes) {
  const TempDir dir;
  const std::string raw(8, '\0');
  auto daqmx_error = [&](const std::string& index, std::uint32_t toc = kTocDaqmx) {
    return error_of(dir, one_channel_file(index, toc, raw), "g/c");
  };
  EXPECT_EQ(daqmx_error(daqmx_index(2, 3, 0, 0, {4})), "");
  EXPECT_TRUE(contains(daqmx_error(daqmx_index(2, 3, 0, 0, {4}), kTocFirst),
                       "a DAQmx raw data index in a segment without DAQmx raw data"));
  EXPECT_TRUE(
      contains(error_of(dir, one_channel_file(plain_index_bytes(kTdsU8, 8), kTocDaqmx, raw)),
               "channel \"/'g'/'c'\": a plain raw data index in a DAQmx segment"));
  EXPECT_TRUE(
      contains(daqmx_error(daqmx_index(2, 12, 0, 0, {4})), "DAQmx scaler 0: unknown data type 12"));
  EXPECT_TRUE(contains(daqmx_error(daqmx_index(2, 3, 1, 0, {4})),
                       "DAQmx scaler 0 reads raw buffer 1, but there are 1"));
  EXPECT_TRUE(contains(daqmx_error(daqmx_index(2, 3, 0, 3, {4})),
                       "DAQmx scaler 0 reads bytes up to 5 of a 4-byte stride"));
  EXPECT_TRUE(contains(daqmx_error(daqmx_index(2, 3, 0, 0, {0})), "raw buffer 0 has width 0"));
  EXPECT_TRUE(contains(daqmx_error(daqmx_index(40, 3, 0, 0, {4})),
                       "raw buffer 0 of 40 values of 4 bytes would be larger than the file"));
  EXPECT_TRUE(contains(daqmx_error(daqmx_index(2, 3, 0, 0, {4}, 0, 4000000)),
                       "it declares 4000000 DAQmx scalers, which the metadata cannot hold"));
  EXPECT_TRUE(
      contains(daqmx_error(daqmx_index(2, 3, 0, 0, {4}, 0, 0)), "it declares 0 DAQmx scalers"));
  std::string many_widths = daqmx_index(2, 3, 0, 0, {4});
  many_widths.replace(many_widths.size() - 8, 4, std::string("\xff\xff\xff\x0f", 4));
  EXPECT_TRUE(
      contains(daqmx_error(many_widths), "raw data widths, which the metadata cannot hold"));
  std::string not_raw = daqmx_index(2, 3, 0, 0, {4});
  not_raw.replace(4, 4, std::string("\x20\0\0\0", 4));  // data type string
  EXPECT_TRUE(contains(daqmx_error(not_raw),
                       "DAQmx raw data of data type string (0x20) is not "
                       "read"));
  std::string dimension = daqmx_index(2, 3, 0, 0, {4});
  dimension[8] = 3;
  EXPECT_TRUE(contains(daqmx_error(dimension), "array dimension 3"));
  std::string digital_float = daqmx_index(2, 9, 0, 0, {4});
  digital_float[0] = 0x6A;  // a digital line scaler (17 bytes) of float64
  digital_float.erase(4 + 4 + 4 + 8 + 4 + 12 + 1, 3);  // its 1-byte sample format bitmap
  EXPECT_TRUE(contains(daqmx_error(digital_float), "a digital line scaler of data type float64"));
  // Two scalers and no scale to pick one.
  EXPECT_TRUE(contains(daqmx_error(daqmx_index(2, 3, 0, 0, {4}, 0, 2)),
                       "2 DAQmx scalers and no NI_Scale property picks one"));

  // Two channels that disagree on the raw buffers.
  TdmsBytes m;
  m.u32(2);
  m.str("/'g'/'a'").raw(daqmx_index(2, 3, 0, 0, {4})).u32(0);
  m.str("/'g'/'b'").raw(daqmx_index(2, 3, 0, 2, {8})).u32(0);
  EXPECT_TRUE(contains(error_of(dir, tdms_segment(kTocDaqmx, m.bytes(), raw)),
                       "channel \"/'g'/'b'\": its raw data widths differ from those of the other "
                       "channels"));
  TdmsBytes n;
  n.u32(2);
  n.str("/'g'/'a'").raw(daqmx_index(2, 3, 0, 0, {4})).u32(0);
  n.str("/'g'/'b'").raw(daqmx_index(1, 3, 0, 2, {4})).u32(0);
  EXPECT_TRUE(contains(error_of(dir, tdms_segment(kTocDaqmx, n.bytes(), raw)),
                       "raw buffer 0 holds 2 values per chunk for one channel and 1 for another"));
}

// A DAQmx channel "g/c" (int16 at byte 0 of a 4-byte stride, scale ID 0) with `properties`.
std::string scaled_file(const std::vector<std::pair<std::string, std::string>>& properties) {
  TdmsBytes m;
  m.u32(1);                                              // 1 object
  m.str("/'g'/'c'");                                     // channel c
  m.raw(daqmx_index(2, 3, 0, 0, {4}));                   //   DAQmx raw data index
  m.u32(static_cast<std::uint32_t>(properties.size()));  // properties, each name and type+value
  for (const auto& [name, typed_value] : properties) m.str(name).raw(typed_value);
  return tdms_segment(kTocDaqmx, m.bytes(), std::string(8, '\x01'));
}

std::string string_value(const std::string& text) {
  TdmsBytes value;
  value.u32(kTdsString).str(text);
  return value.bytes();
}

std::string double_value(double number) {
  TdmsBytes value;
  value.u32(kTdsF64).f64(number);
  return value.bytes();
}

TEST(TdmsReader, RefusesScalesItDoesNotRead) {
  const TempDir dir;
  const std::string path = dir.file("bad.tdms");
  auto scale_error = [&](const std::vector<std::pair<std::string, std::string>>& properties) {
    return error_of(dir, scaled_file(properties), "g/c");
  };
  EXPECT_EQ(scale_error({{"NI_Number_Of_Scales", double_value(2)},
                         {"NI_Scale[1]_Scale_Type", string_value("Polynomial")}}),
            path +
                ": \"g/c\": NI_Scale[1]_Scale_Type is \"Polynomial\": only Linear scales are "
                "read");
  EXPECT_TRUE(contains(scale_error({{"NI_Number_Of_Scales", double_value(1.5)}}),
                       "NI_Number_Of_Scales is 1.5"));
  EXPECT_TRUE(contains(scale_error({{"NI_Number_Of_Scales", double_value(2)},
                                    {"NI_Scale[1]_Scale_Type", string_value("Linear")},
                                    {"NI_Scale[1]_Linear_Slope", double_value(2)}}),
                       "NI_Scale[1]_Linear_Slope or NI_Scale[1]_Linear_Y_Intercept is missing"));
  EXPECT_TRUE(contains(scale_error({{"NI_Number_Of_Scales", double_value(2)},
                                    {"NI_Scale[1]_Scale_Type", string_value("Linear")},
                                    {"NI_Scale[1]_Linear_Slope", double_value(2)},
                                    {"NI_Scale[1]_Linear_Y_Intercept", double_value(0)},
                                    {"NI_Scale[1]_Linear_Input_Source", double_value(1)}}),
                       "NI_Scale[1]_Linear_Input_Source 1 is not an earlier scale"));
  EXPECT_TRUE(contains(scale_error({{"NI_Number_Of_Scales", double_value(4)}}),
                       "no DAQmx scaler has scale ID 3"));
  // "scaled": the values are already scaled; a Linear scale with the raw values as its input.
  testing::write_file(path, scaled_file({{"NI_Scaling_Status", string_value("scaled")},
                                         {"NI_Number_Of_Scales", double_value(2)},
                                         {"NI_Scale[1]_Scale_Type", string_value("Polynomial")}}));
  EXPECT_EQ(read_named(path, "g/c"), (std::vector<double>{257, 257}));
  testing::write_file(
      path, scaled_file({{"NI_Number_Of_Scales", double_value(1)},
                         {"NI_Scale[0]_Scale_Type", string_value("Linear")},
                         {"NI_Scale[0]_Linear_Slope", double_value(-1)},
                         {"NI_Scale[0]_Linear_Y_Intercept", double_value(0.5)},
                         {"NI_Scale[0]_Linear_Input_Source", double_value(4294967295.0)}}));
  EXPECT_EQ(read_named(path, "g/c"), (std::vector<double>{-256.5, -256.5}));
}

TEST(TdmsReader, RefusesTwoChannelsOfOneNameAndChannelsTheFileDoesNotHold) {
  const TempDir dir;
  TdmsBytes m;
  m.u32(2);
  m.str("/'a/b'/'c'").raw(plain_index_bytes(kTdsU8, 1)).u32(0);  // group "a/b", channel "c"
  m.str("/'a'/'b/c'").raw(plain_index_bytes(kTdsU8, 1)).u32(0);  // group "a", channel "b/c"
  EXPECT_TRUE(contains(error_of(dir, tdms_segment(kTocFirst, m.bytes(), "\x01\x02"), "a/b/c"),
                       "two channels are named \"a/b/c\" (\"/'a/b'/'c'\" and \"/'a'/'b/c'\")"));
  const std::string path = dir.file("run.tdms");
  testing::write_file(path, contiguous_float64_file());
  EXPECT_EQ(input_error_of([&] {
              FileSignal missing;
              missing.name = "nope/x";
              tdms().read_signal(path, missing, -1);
            }),
            path + ": the file holds no channel \"nope/x\"");
  Sidecar sidecar;
  sidecar.sample_rate_hz = 500.0;
  sidecar.channels = {channel("base", ChannelRole::Base, Quantity::Acceleration, "m/s^2")};
  sidecar.channels[0].source = "Dr. T's table/nope";
  const std::string message = input_error_of([&] { read_recording(path, sidecar); });
  EXPECT_TRUE(contains(message,
                       "reads \"Dr. T's table/nope\", which the file does not hold (it "
                       "holds \"Dr. T's table/base/acc\", \"Dr. T's table/force\""))
      << message;
  sidecar.channels[0].source = "Dr. T's table/base/acc";
  sidecar.sample_rate_hz = 400.0;  // the file's wf_increment says 500 Hz
  EXPECT_TRUE(contains(input_error_of([&] { read_recording(path, sidecar); }),
                       "is sampled at 500 Hz, the sidecar given says sample_rate_hz 400"));
}

TEST(TdmsReader, RefusesAMissingFileAndAColumnOfAVector) {
  const TempDir dir;
  EXPECT_EQ(input_error_of([&] { tdms().describe(dir.file("none.tdms")); }),
            dir.file("none.tdms") + ": file not found");
  const std::string path = dir.file("run.tdms");
  testing::write_file(path, contiguous_float64_file());
  const FileContents contents = tdms().describe(path);
  EXPECT_EQ(input_error_of([&] { tdms().read_signal(path, contents.file_signals[1], 1); }),
            path + ": \"Dr. T's table/force\" has one column, not 2");
}

TEST(TdmsReader, SaysSoWhenALastSegmentWithoutDataIsCutShort) {
  const TempDir dir;
  const std::string path = dir.file("cut.tdms");
  TdmsBytes m;
  m.u32(1).str("/").u32(kIndexNoData).u32(0);  // 1 object: the file, no data, no properties
  testing::write_file(path, contiguous_float64_file() +
                                tdms_lead_in(kTocMetaData, 4713, 0xFFFFFFFFFFFFFFFFull, m.size()) +
                                m.bytes());
  EXPECT_EQ(tdms().describe(path).container,
            "NI TDMS (version 4713), 2 segments; segment 1 is cut short (a file still being "
            "written?); it holds no raw data");
}

TEST(TdmsReader, ReplacesBytesThatAreNotUtf8InNamesAndProperties) {
  const TempDir dir;
  TdmsBytes m;
  m.u32(1).str("/'g\xff'/'c'").raw(plain_index_bytes(kTdsU8, 1));
  m.u32(1).str("n\xc3").u32(kTdsString).str("\xed\xa0\x80 v");  // a lone surrogate
  const std::string path = dir.file("utf8.tdms");
  testing::write_file(path, tdms_segment(kTocFirst, m.bytes(), "\x05"));
  const FileContents contents = tdms().describe(path);
  ASSERT_EQ(contents.file_signals.size(), 1u);
  EXPECT_EQ(contents.file_signals[0].name, "g\xEF\xBF\xBD/c");
  EXPECT_EQ(contents.file_signals[0].properties["n\xEF\xBF\xBD"],
            "\xEF\xBF\xBD\xEF\xBF\xBD\xEF\xBF\xBD v");
  EXPECT_EQ(tdms().read_signal(path, contents.file_signals[0], -1), (std::vector<double>{5}));
}

}  // namespace
}  // namespace oscilab::daq
