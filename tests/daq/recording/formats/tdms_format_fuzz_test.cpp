// Mutated TDMS files: the reader either reads them or throws InputError; it never crashes, hangs,
// throws anything else or allocates far beyond what the file's size justifies. Fixed seeds, so a
// failure reproduces.
#include <gtest/gtest.h>

#include <cstdint>
#include <exception>
#include <limits>
#include <random>
#include <string>
#include <typeinfo>
#include <vector>

#include "analysis/common/input_error.h"
#include "daq/recording/formats/formats.h"
#include "daq/recording/recording.h"
#include "tests/daq/recording/formats/tdms_test_bytes.h"
#include "tests/daq/recording/fuzz_mutation.h"
#include "tests/daq/recording/largest_allocation.h"
#include "tests/daq/recording/recording_test_util.h"

namespace oscilab::daq {
namespace {

using namespace testing;  // the TDMS building blocks of tdms_test_bytes.h, the mutations
using testing::channel;
using testing::TempDir;

struct Seed {
  std::string bytes;
  std::string first;  // two signals a sidecar maps
  std::string second;
  bool big_endian = false;
};

void index_f64(TdmsBytes& m, std::uint64_t values) {
  m.u32(kIndexPlain).u32(kTdsF64).u32(1).u64(values);  // length, float64, dimension, values
}

// Two float64 channels at 100 Hz in one contiguous segment, with properties of several types.
Seed contiguous_seed() {
  TdmsBytes m;
  m.u32(3);                                    // 3 objects
  m.str("/").u32(kIndexNoData).u32(2);         // the file: no data, 2 properties
  m.str("title").u32(kTdsString).str("fuzz");  //   string
  m.str("t0").u32(kTdsTimestamp).u64(1ull << 63).number<std::int64_t>(3029529600);  // timestamp
  m.str("/'g'/'a'");                                                                // channel a
  index_f64(m, 6);                               //   float64, 6 values per chunk
  m.u32(2);                                      //   2 properties
  m.str("wf_increment").u32(kTdsF64).f64(0.01);  //   100 Hz
  m.str("unit_string").u32(kTdsString).str("V");
  m.str("/'g'/'b'");  // channel b
  index_f64(m, 6);    //   float64, 6 values per chunk
  m.u32(1);           //   1 property
  m.str("wf_increment").u32(kTdsF64).f64(0.01);
  TdmsBytes raw;
  for (int i = 0; i < 24; ++i) raw.f64(0.25 * i - 1.0);  // 2 chunks
  return {tdms_segment(kTocMetaData | kTocNewObjList | kTocRawData, m.bytes(), raw.bytes()), "g/a",
          "g/b"};
}

// Interleaved big-endian int32 in two segments, the second without metadata.
Seed interleaved_seed() {
  const std::uint32_t toc =
      kTocMetaData | kTocNewObjList | kTocRawData | kTocInterleavedData | kTocBigEndian;
  TdmsBytes m(true);
  m.u32(2);  // 2 objects
  for (const char* name : {"/'g'/'x'", "/'g'/'y'"}) {
    m.str(name);                                    // channel
    m.u32(kIndexPlain).u32(kTdsI32).u32(1).u64(4);  //   int32, 4 values per chunk
    m.u32(1);                                       //   1 property
    m.str("wf_increment").u32(kTdsF64).f64(0.01);
  }
  TdmsBytes raw(true);
  for (int i = 0; i < 8; ++i) raw.i32(i * 1000 - 3);
  return {tdms_segment(toc, m.bytes(), raw.bytes()) +
              tdms_segment(kTocRawData | kTocInterleavedData | kTocBigEndian, "", raw.bytes()),
          "g/x", "g/y", true};
}

// DAQmx int16 with linear scales in two segments, the second reusing the raw data indexes.
Seed daqmx_seed() {
  const std::uint32_t toc =
      kTocMetaData | kTocNewObjList | kTocRawData | kTocInterleavedData | kTocDAQmxRawData;
  TdmsBytes m;
  m.u32(2);  // 2 objects
  for (int c = 0; c < 2; ++c) {
    m.str(c == 0 ? "/'d'/'ai0'" : "/'d'/'ai1'");  // channel
    m.u32(kIndexFormatChangingScaler);            //   DAQmx index
    m.u32(kTdsDaqmxRaw).u32(1).u64(3);            //   DAQmx raw, dimension 1, 3 values
    m.u32(1);                                     //   1 scaler:
    m.u32(3).u32(0).u32(2 * c).u32(0).u32(0);     //   int16, buffer 0, offset, bitmap, ID
    m.u32(1).u32(4);                              //   1 width: 4 bytes
    m.u32(6);                                     //   6 properties
    m.str("NI_Number_Of_Scales").u32(kTdsU32).u32(2);
    m.str("NI_Scale[1]_Scale_Type").u32(kTdsString).str("Linear");
    m.str("NI_Scale[1]_Linear_Slope").u32(kTdsF64).f64(0.001);
    m.str("NI_Scale[1]_Linear_Y_Intercept").u32(kTdsF64).f64(-0.5);
    m.str("NI_Scale[1]_Linear_Input_Source").u32(kTdsU32).u32(0);
    m.str("wf_increment").u32(kTdsF64).f64(0.01);
  }
  TdmsBytes raw;
  for (int i = 0; i < 6; ++i) raw.number<std::int16_t>(static_cast<std::int16_t>(i * 999 - 77));
  TdmsBytes m1;
  m1.u32(2);  // 2 objects, indexes as before
  m1.str("/'d'/'ai0'").u32(kIndexSameAsPrevious).u32(0);
  m1.str("/'d'/'ai1'").u32(kIndexSameAsPrevious).u32(0);
  return {tdms_segment(toc, m.bytes(), raw.bytes()) +
              tdms_segment(toc & ~kTocNewObjList, m1.bytes(), raw.bytes()),
          "d/ai0", "d/ai1"};
}

// Objects added across segments, a digital line, and a last segment still being written.
Seed incremental_seed() {
  TdmsBytes m0;
  m0.u32(1);                                             // 1 object
  m0.str("/'g'/'a'");                                    // channel a
  index_f64(m0, 2);                                      //   float64, 2 values per chunk
  m0.u32(1).str("wf_increment").u32(kTdsF64).f64(0.01);  //   1 property: 100 Hz
  TdmsBytes r0;
  r0.f64(1.0).f64(2.0);
  TdmsBytes m1;
  m1.u32(1);           // 1 object appended
  m1.str("/'g'/'b'");  // channel b
  index_f64(m1, 4);    //   float64, 4 values per chunk
  m1.u32(0);           //   no properties
  TdmsBytes r1;
  for (int i = 0; i < 6; ++i) r1.f64(i);  // 1 chunk of (a: 2 values, b: 4 values)
  const std::string partial(10, '\x11');
  return {tdms_segment(kTocMetaData | kTocNewObjList | kTocRawData, m0.bytes(), r0.bytes()) +
              tdms_lead_in(kTocMetaData | kTocRawData, 4713, 0xFFFFFFFFFFFFFFFFull, m1.size()) +
              m1.bytes() + r1.bytes() + partial,
          "g/a", "g/b"};
}

Seed digital_seed() {
  const std::uint32_t toc =
      kTocMetaData | kTocNewObjList | kTocRawData | kTocInterleavedData | kTocDAQmxRawData;
  TdmsBytes m;
  m.u32(2);  // 2 objects
  for (int line = 0; line < 2; ++line) {
    m.str(line == 0 ? "/'dio'/'l0'" : "/'dio'/'l9'");     // channel
    m.u32(kIndexDigitalLineScaler);                       //   DAQmx digital line index
    m.u32(kTdsDaqmxRaw).u32(1).u64(4);                    //   DAQmx raw, dimension 1, 4 values
    m.u32(1);                                             //   1 scaler:
    m.u32(0).u32(0).u32(line == 0 ? 0 : 9).u8(0).u32(0);  //  uint8, buffer, bit, bitmap, ID
    m.u32(1).u32(2);                                      //   1 width: 2 bytes
    m.u32(0);                                             //   no properties
  }
  return {tdms_segment(toc, m.bytes(), std::string("\x01\x02\x00\x00\x01\x00\xff\xff", 8)),
          "dio/l0", "dio/l9"};
}

// Values every numeric field is set to: counts, lengths, offsets, types and flags at their
// extremes, and floats (rates, scales) that are not numbers, infinite, tiny (a rate far beyond
// Nyquist) or huge.
const std::vector<FieldValue> kExtremes = {
    {0, 4},
    {0xFFFFFFFF, 4},
    {0x7FFFFFFF, 4},
    {0x80000000, 4},
    {1, 4},
    {0xFFFFFFFFFFFFFFFFull, 8},
    {0x7FFFFFFFFFFFFFFFull, 8},
    {0, 8},
    {bits_of(std::numeric_limits<double>::quiet_NaN()), 8},
    {bits_of(std::numeric_limits<double>::infinity()), 8},
    {bits_of(-1.0), 8},
    {bits_of(1e-310), 8},
    {bits_of(1e308), 8},
};

std::string mutate(std::string bytes, bool big_endian, std::mt19937_64& rng) {
  switch (std::uniform_int_distribution<int>(0, 5)(rng)) {
    case 0:
      truncate_anywhere(bytes, rng);
      break;
    case 1:
      flip_bits(bytes, 1 + static_cast<int>(rng() % 8), rng);
      break;
    case 2: {  // inserted random bytes
      const std::size_t at = random_position(bytes.size(), rng);
      bytes.insert(at, random_bytes(1 + rng() % 16, rng));
      break;
    }
    case 3: {  // deleted range
      const std::size_t at = random_position(bytes.size(), rng);
      bytes.erase(at, 1 + rng() % 32);
      break;
    }
    case 4: {  // a repeated range (a duplicated segment or field)
      const std::size_t at = random_position(bytes.size(), rng);
      repeat_range(bytes, at, 1 + rng() % 64, rng);
      break;
    }
    default: {  // a field set to an extreme, in the file's byte order three times in four
      const FieldValue& extreme = kExtremes[rng() % kExtremes.size()];
      if (!bytes.empty()) {
        put_field(bytes, random_position(bytes.size() - 1, rng), extreme.value, extreme.width,
                  (rng() % 4 == 0) != big_endian);
      }
      break;
    }
  }
  return bytes;
}

// Reads `path` the ways a user can: describe, every signal, and a recording through a sidecar.
void read_every_way(const std::string& path, const Seed& seed) {
  const auto& format = dynamic_cast<const SignalFileReader&>(tdms_format());
  try {
    const FileContents contents = format.describe(path);
    (void)contents.properties.dump();
    for (const FileSignal& signal : contents.file_signals)
      (void)format.read_signal(path, signal, -1);
  } catch (const InputError&) {
  }
  Sidecar sidecar;
  sidecar.sample_rate_hz = 100.0;
  sidecar.channels = {channel("a", ChannelRole::Base, Quantity::Acceleration, "V"),
                      channel("b", ChannelRole::Mass, Quantity::Acceleration, "V")};
  sidecar.channels[0].source = seed.first;
  sidecar.channels[1].source = seed.second;
  try {
    (void)read_recording(path, sidecar);
  } catch (const InputError&) {
  }
}

// Largest single allocation allowed while reading a file of `size` bytes: the values of the two
// mapped channels as doubles (8 bytes per stored byte each, 16 in all) and the reader's
// per-object bookkeeping (under 32 bytes per metadata byte), plus 64 KiB for messages, JSON and
// stream buffers. A count or size taken from the file unchecked (up to 2^64) would exceed it;
// on these few-hundred-byte files the largest request seen is a stream's 8 KiB buffer.
std::size_t allocation_bound(std::size_t size) { return 32 * size + 65536; }

void run_case(const std::string& path, const std::string& bytes, const Seed& seed,
              const std::string& what) {
  testing::write_file(path, bytes);
  start_tracking_allocations();
  try {
    read_every_way(path, seed);
  } catch (const std::exception& error) {
    stop_tracking_allocations();
    FAIL() << what << ": " << typeid(error).name() << ": " << error.what();
  } catch (...) {
    stop_tracking_allocations();
    FAIL() << what << ": a non-standard exception";
  }
  const std::size_t largest_bytes = stop_tracking_allocations();
  EXPECT_LE(largest_bytes, allocation_bound(bytes.size()))
      << what << ": " << largest_bytes << " bytes for a file of " << bytes.size();
}

std::vector<Seed> seeds() {
  return {contiguous_seed(), interleaved_seed(), daqmx_seed(), incremental_seed(), digital_seed()};
}

TEST(TdmsFuzz, SeedsReadCleanly) {
  const TempDir dir;
  for (const Seed& seed : seeds()) {
    testing::write_file(dir.file("seed.tdms"), seed.bytes);
    Sidecar sidecar;
    sidecar.sample_rate_hz = 100.0;
    sidecar.channels = {channel("a", ChannelRole::Base, Quantity::Acceleration, "V"),
                        channel("b", ChannelRole::Mass, Quantity::Acceleration, "V")};
    sidecar.channels[0].source = seed.first;
    sidecar.channels[1].source = seed.second;
    EXPECT_GT(read_recording(dir.file("seed.tdms"), sidecar).sample_count(), 0) << seed.first;
  }
}

TEST(TdmsFuzz, EveryFieldAtItsExtremesGivesAnInputErrorOrARecording) {
  const TempDir dir;
  const std::string path = dir.file("field.tdms");
  int cases = 0;
  for (const Seed& seed : seeds()) {
    for (std::size_t at = 0; at < seed.bytes.size(); ++at) {
      for (const FieldValue& extreme : kExtremes) {
        std::string bytes = seed.bytes;
        put_field(bytes, at, extreme.value, extreme.width, seed.big_endian);
        run_case(path, bytes, seed,
                 seed.first + " seed, byte " + std::to_string(at) + " = " +
                     std::to_string(extreme.value));
        if (HasFatalFailure()) return;
        ++cases;
      }
    }
  }
  EXPECT_GT(cases, 10000);
}

TEST(TdmsFuzz, TenThousandMutatedFilesGiveAnInputErrorOrARecording) {
  const TempDir dir;
  const std::string path = dir.file("mutated.tdms");
  const std::vector<Seed> all = seeds();
  std::mt19937_64 rng(20240611);
  for (int iteration = 0; iteration < 10000; ++iteration) {
    const Seed& seed = all[static_cast<std::size_t>(iteration) % all.size()];
    std::string bytes = seed.bytes;
    for (int m = 0, n = 1 + static_cast<int>(rng() % 3); m < n; ++m) {
      bytes = mutate(std::move(bytes), seed.big_endian, rng);
    }
    run_case(path, bytes, seed, "iteration " + std::to_string(iteration) + " (seed 20240611)");
    if (HasFatalFailure()) return;
  }
}

}  // namespace
}  // namespace oscilab::daq
