// The NI TDMS reader's refusals: files built here byte by byte from NI's "TDMS File Format
// Internal Structure", every field commented, each broken in one way, and the one error each
// raises (naming the file, the object or the offset).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "daq/recording/format_reader.h"
#include "daq/recording/formats/formats.h"
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
