// The NI TDMS reader against files real instruments wrote (NI-DAQmx logging, LabVIEW
// SignalExpress) and against files built here byte by byte from NI's "TDMS File Format Internal
// Structure", every field commented.
#include <gtest/gtest.h>

#include "tests/instrument_files.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "daq/recording/format_reader.h"
#include "daq/recording/formats/formats.h"
#include "daq/recording/recording.h"
#include "tests/daq/recording/formats/tdms_reader_checks.h"
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

double rms(const std::vector<double>& values) {
  double sum = 0.0;
  for (const double value : values) sum += value * value;
  return std::sqrt(sum / static_cast<double>(values.size()));
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

// What a Silixa iDAS interrogator writes: one segment, its ToC saying interleaved data, 1152
// int16 channels of 1000 samples each (one row per sample time, every channel in it), the rate
// only in a root property "SamplingFrequency[Hz]". 1152 × 1000 × 2 bytes is exactly one chunk.
TEST(TdmsReader, ReadsADasFileOfManyInterleavedChannelsInOneChunk) {
  constexpr int kChannels = 1152;
  constexpr int kSamples = 1000;
  const std::uint32_t toc = kTocMetaData | kTocNewObjList | kTocRawData | kTocInterleavedData;
  TdmsBytes m(false);    // metadata, little-endian
  m.u32(2 + kChannels);  // objects: the root, one group, 1152 channels
  m.str("/");            // object 0: the file (root)
  m.u32(kIndexNoData);   //   no raw data
  m.u32(1);              //   1 property:
  m.str("SamplingFrequency[Hz]").u32(kTdsF64).f64(1000.0);  // the rate, 1 kHz
  m.str("/'Measurement'");                                  // object 1: group "Measurement"
  m.u32(kIndexNoData);                                      //   no raw data
  m.u32(0);                                                 //   no properties
  for (int c = 0; c < kChannels; ++c) {
    m.str("/'Measurement'/'" + std::to_string(c) + "'");  // a channel, named by its index
    m.u32(kIndexPlain);                                   //   raw data index of 20 bytes:
    m.u32(kTdsI16);                                       //     int16
    m.u32(1);                                             //     array dimension 1
    m.u64(kSamples);                                      //     1000 values per chunk
    m.u32(0);                                             //   no properties
  }
  TdmsBytes raw(false);  // 1000 rows of 1152 int16 values: channel c at row r holds c − r
  for (int r = 0; r < kSamples; ++r) {
    for (int c = 0; c < kChannels; ++c) raw.number<std::int16_t>(static_cast<std::int16_t>(c - r));
  }
  ASSERT_EQ(raw.bytes().size(), 2304000u);  // exactly one chunk
  const TempDir dir;
  const std::string path = dir.file("idas.tdms");
  testing::write_file(path, tdms_segment(toc, m.bytes(), raw.bytes()));
  const FileContents contents = tdms().describe(path);
  EXPECT_EQ(contents.file_signals.size(), static_cast<std::size_t>(kChannels));
  EXPECT_EQ(contents.properties["file"]["SamplingFrequency[Hz]"], 1000.0);
  // No wf_increment: the rate is the file's SamplingFrequency[Hz].
  EXPECT_EQ(signal_named(contents, "Measurement/1151").sample_rate_hz, 1000.0);
  for (int c : {0, 1, 575, 1151}) {
    const std::vector<double> values = read_named(path, "Measurement/" + std::to_string(c));
    ASSERT_EQ(values.size(), static_cast<std::size_t>(kSamples)) << c;
    EXPECT_EQ(values.front(), c);
    EXPECT_EQ(values[999], c - 999);
  }
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

}  // namespace
}  // namespace oscilab::daq
