// The UFF 58 reader: real instruments' files, files built field by field from the dataset 58
// description (uff_test_files.h), a round trip through Oscilab's own UFF 58 writer, the same
// values through CSV, and every refusal.
#include <gtest/gtest.h>

#include "tests/instrument_files.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "analysis/common/input_error.h"
#include "daq/export/uff58_export.h"
#include "daq/recording/format_reader.h"
#include "daq/recording/formats/formats.h"
#include "daq/recording/recording.h"
#include "tests/daq/recording/formats/uff_test_files.h"
#include "tests/daq/recording/recording_test_util.h"

namespace oscilab::daq {
namespace {

using testing::ascii_uff58;
using testing::binary_uff58;
using testing::channel;
using testing::e13_lines;
using testing::ieee_bytes;
using testing::input_error_of;
using testing::TempDir;
using testing::Uff58Header;
using testing::write_file;

const std::string kFixtures = oscilab::testing::instrument_files() + "/uff/";

// A one-channel sidecar that reads `source` as volts (factor 1: samples_si = stored values).
Sidecar volts_sidecar(double rate_hz, const std::string& source) {
  Sidecar sidecar;
  sidecar.sample_rate_hz = rate_hz;
  sidecar.channels = {channel("p", ChannelRole::Force, Quantity::Force, "V")};
  sidecar.channels[0].source = source;
  return sidecar;
}

const SignalFileReader& uff_signals() {
  return dynamic_cast<const SignalFileReader&>(uff_format());
}

double rms(const Eigen::VectorXd& x) { return std::sqrt(x.squaredNorm() / x.size()); }

std::vector<double> column(const Recording& recording, Eigen::Index c) {
  const Eigen::VectorXd x = recording.samples_si.col(c);
  return {x.data(), x.data() + x.size()};
}

// --- Real files -------------------------------------------------------------------------------

TEST(UffFormat, DescribesTheAsciiMicrophoneRecording) {
  OSCILAB_SKIP_WITHOUT_INSTRUMENT_FILES();
  const std::string path = kFixtures + "Sample_UFF58_ascii.uff";
  ASSERT_EQ(&format_for_file(path), &uff_format());
  const FileContents contents = uff_format().describe(path);
  ASSERT_EQ(contents.file_signals.size(), 1u);
  const FileSignal& signal = contents.file_signals[0];
  // Record 6: response entity "Mic 01", node 0, direction 1 (+X).
  EXPECT_EQ(signal.name, "Mic 01:0:+X");
  EXPECT_EQ(signal.sample_count, 79292);
  EXPECT_EQ(signal.unit, "Pa");
  // 1.52588E-05 s (6 digits) is 65 536.2 Hz; 65 536 Hz lies within its rounding.
  ASSERT_TRUE(signal.sample_rate_hz);
  EXPECT_EQ(*signal.sample_rate_hz, 65536.0);
  EXPECT_EQ(signal.stored_type, "text, real single");
  EXPECT_EQ(signal.properties["id_lines"][0], "Mic 01.0Scalar");
  EXPECT_EQ(signal.properties["id_lines"][2], "18-Apr-16 13:49:58");
  EXPECT_EQ(signal.properties["abscissa"]["specific_data_type"], 17);
  EXPECT_EQ(signal.properties["ordinate"]["specific_data_type"], 21);
  EXPECT_EQ(signal.properties["ordinate"]["label"], "Pressure");
  EXPECT_EQ(signal.properties["alias"], "dataset 1");
  EXPECT_EQ(contents.container, "UFF 58, 1 time response");
  EXPECT_TRUE(contents.properties["skipped_datasets"].empty());
}

TEST(UffFormat, ReadsTheMicrophoneRecordingAlikeFromAsciiAndBinary) {
  OSCILAB_SKIP_WITHOUT_INSTRUMENT_FILES();
  const std::string ascii_path = kFixtures + "Sample_UFF58_ascii.uff";
  const std::string binary_path = kFixtures + "Sample_UFF58b_bin.uff";
  const FileContents binary_contents = uff_format().describe(binary_path);
  ASSERT_EQ(binary_contents.file_signals.size(), 1u);
  EXPECT_EQ(binary_contents.file_signals[0].name, "Mic 01:0:+X");
  EXPECT_EQ(binary_contents.file_signals[0].stored_type, "float32");
  EXPECT_EQ(binary_contents.file_signals[0].properties["storage"]["byte_order"], "little-endian");
  EXPECT_EQ(binary_contents.file_signals[0].properties["storage"]["bytes"], 317168);  // 79 292 × 4
  EXPECT_EQ(binary_contents.container, "UFF 58b, little-endian, 1 time response");

  const Recording ascii = read_recording(ascii_path, volts_sidecar(65536.0, "Mic 01:0:+X"));
  const Recording binary = read_recording(binary_path, volts_sidecar(65536.0, "dataset 1"));
  ASSERT_EQ(ascii.sample_count(), 79292);
  ASSERT_EQ(binary.sample_count(), 79292);
  EXPECT_EQ(binary.sidecar.channels[0].source, "dataset 1");  // the sidecar as given
  // The first and last values as the ASCII file prints them.
  EXPECT_EQ(ascii.samples_si(0, 0), -1.47553e-02);
  EXPECT_EQ(ascii.samples_si(79291, 0), -4.31469e-03);
  // E13.5 keeps 6 digits of the float32 values: |difference| ≤ 5e-7 (README, measured).
  EXPECT_LE((ascii.samples_si - binary.samples_si).cwiseAbs().maxCoeff(), 5e-7);
  EXPECT_GT((ascii.samples_si - binary.samples_si).cwiseAbs().maxCoeff(), 0.0);  // two readings
  EXPECT_NEAR(binary.samples_si(0, 0), -1.47553e-02, 5e-8);
  // RMS 0.01434 Pa (README, 4 digits).
  EXPECT_NEAR(rms(ascii.samples_si.col(0)), 0.01434, 5e-6);
  EXPECT_NEAR(rms(binary.samples_si.col(0)), 0.01434, 5e-6);
  EXPECT_EQ(binary.container, "UFF 58b, little-endian, 1 time response");
}

TEST(UffFormat, ReadsTheCatmanFileWithThreeDigitExponentsAndAShortLastLine) {
  OSCILAB_SKIP_WITHOUT_INSTRUMENT_FILES();
  const std::string path = kFixtures + "time-history-not-all-columns-filled.uff";
  const FileContents contents = uff_format().describe(path);
  ASSERT_EQ(contents.file_signals.size(), 1u);
  const FileSignal& signal = contents.file_signals[0];
  EXPECT_EQ(signal.name, "dataset 1");  // record 6 names no DOF (NONE, node 0)
  EXPECT_EQ(signal.sample_count, 13);
  EXPECT_EQ(signal.unit, "m/s\u00B2");  // UTF-8 '²'
  ASSERT_TRUE(signal.sample_rate_hz);
  EXPECT_EQ(*signal.sample_rate_hz, 20000.0);  // dt 5.00000E-005 s
  EXPECT_EQ(signal.properties["id_lines"][0], "1x : m/s\u00B2");
  EXPECT_EQ(signal.properties["id_lines"][1], "UFF58 file created by HBM catman");

  Sidecar sidecar = volts_sidecar(20000.0, "dataset 1");
  sidecar.channels = {channel("a", ChannelRole::Base, Quantity::Acceleration, "m/s^2")};
  sidecar.channels[0].source = "dataset 1";
  const Recording recording = read_recording(path, sidecar);
  const std::vector<double> expected = {-3.81956, -3.56616, -2.98987, -2.62207, -3.22879,
                                        -3.63712, -3.90210, -3.69214, -3.42426, -3.48508,
                                        -4.03966, -3.46046, -5.84096};
  EXPECT_EQ(column(recording, 0), expected);
}

// --- Files built from the dataset 58 description --------------------------------------------

struct BinaryCase {
  int byte_order;  // 1 little-endian, 2 big-endian
  bool float64;
};

class UffBinary : public ::testing::TestWithParam<BinaryCase> {};

TEST_P(UffBinary, ReadsEachByteOrderAndPrecision) {
  const BinaryCase c = GetParam();
  // Values exact in float32 as well, plus one that is not (0.1) and a float64-only extreme.
  const std::vector<double> values = {0.5, -1.25, 3.0e4, 0.1, -2.0e-3, c.float64 ? 1e300 : 7.0};
  std::string data;
  std::vector<double> expected;
  for (const double v : values) {
    data += c.float64 ? ieee_bytes<double>(v, c.byte_order)
                      : ieee_bytes<float>(static_cast<float>(v), c.byte_order);
    expected.push_back(c.float64 ? v : static_cast<double>(static_cast<float>(v)));
  }
  Uff58Header h;
  h.ordinate_type = c.float64 ? "4" : "2";  // real double / real single
  h.count = "6";
  h.increment = "2.00000E-03";  // 500 Hz
  h.eol = "\r\n";
  const TempDir dir;
  const std::string path = dir.file("b.uff");
  write_file(path, binary_uff58(h, c.byte_order, data));
  const FileContents contents = uff_format().describe(path);
  ASSERT_EQ(contents.file_signals.size(), 1u);
  EXPECT_EQ(contents.file_signals[0].name, "mic:3:-Y");
  EXPECT_EQ(contents.file_signals[0].stored_type, c.float64 ? "float64" : "float32");
  EXPECT_EQ(*contents.file_signals[0].sample_rate_hz, 500.0);
  EXPECT_EQ(uff_signals().read_signal(path, contents.file_signals[0], -1), expected);
  const Recording recording = read_recording(path, volts_sidecar(500.0, "mic:3:-Y"));
  EXPECT_EQ(column(recording, 0), expected);
  EXPECT_EQ(recording.container, std::string("UFF 58b, ") + (c.byte_order == 1 ? "little" : "big") +
                                     "-endian, 1 time response");
}

INSTANTIATE_TEST_SUITE_P(ByteOrders, UffBinary,
                         ::testing::Values(BinaryCase{1, false}, BinaryCase{2, false},
                                           BinaryCase{1, true}, BinaryCase{2, true}));

TEST(UffFormat, ReadsBinaryDataFollowedByANewline) {
  Uff58Header h;
  h.count = "2";
  std::string data = ieee_bytes<float>(1.5F, 1) + ieee_bytes<float>(-2.0F, 1);
  std::string file = binary_uff58(h, 1, data);
  file.insert(file.size() - 7, "\n");  // a newline between the data and the closing "-1"
  const TempDir dir;
  write_file(dir.file("n.uff"), file);
  const Recording recording = read_recording(dir.file("n.uff"), volts_sidecar(1000.0, "mic:3:-Y"));
  EXPECT_EQ(column(recording, 0), (std::vector<double>{1.5, -2.0}));
}

// Read under an opening's control (the app's review): one report per signal the sidecar maps, and
// a cancelled token stops the read before its first signal.
TEST(UffFormat, AControlledReadReportsEachSignalAndStopsWhenCancelled) {
  Uff58Header h;
  h.count = "2";
  const TempDir dir;
  write_file(dir.file("c.uff"),
             binary_uff58(h, 1, ieee_bytes<float>(1.5F, 1) + ieee_bytes<float>(-2.0F, 1)));
  const Sidecar sidecar = volts_sidecar(1000.0, "mic:3:-Y");
  OpeningControl control;
  std::vector<double> reports;
  control.progress = [&](double f) { reports.push_back(f); };
  const Recording recording =
      uff_format().read_controlled(dir.file("c.uff"), sidecar, "the sidecar", control);
  EXPECT_EQ(column(recording, 0), (std::vector<double>{1.5, -2.0}));
  EXPECT_EQ(reports, (std::vector<double>{1.0}));
  control.cancel.cancel();
  EXPECT_THROW(uff_format().read_controlled(dir.file("c.uff"), sidecar, "the sidecar", control),
               OpeningCancelled);
}

// A file as a modal test program writes it: header 151, units 164, a frequency response (58,
// function type 4, complex), two time responses (one binary, CRLF), nodes 2411, and a binary FRF
// whose data happen to hold the bytes of a "-1" line.
std::string mixed_file() {
  std::string file;
  file += "    -1\n   151\nmodel\nNONE\n    -1\n";  // 1: header
  file +=
      "    -1\n   164\n         1SI                           2\n"
      "  1.00000000000000000D+00  1.00000000000000000D+00  1.00000000000000000D+00\n"
      "  2.73150000000000000D+02\n    -1\n";  // 2: units
  Uff58Header frf;
  frf.function_type = "4";  // frequency response function
  frf.ordinate_type = "5";  // complex single: refused for a time response, skipped here
  frf.count = "2";
  frf.increment = "1.00000E+00";
  frf.abscissa_units = "Hz";
  file += ascii_uff58(frf, e13_lines({1.0, 0.0, 0.5, -0.5}));  // 3: FRF
  Uff58Header a;
  a.response_entity = "base";
  a.response_node = "1";
  a.response_direction = "3";  // +Z
  a.count = "3";
  file += ascii_uff58(a, e13_lines({0.25, -0.5, 0.75}));  // 4
  Uff58Header b;
  b.response_entity = "mass";
  b.response_node = "2";
  b.response_direction = "3";
  b.ordinate_type = "4";
  b.count = "3";
  b.eol = "\r\n";
  file += binary_uff58(
      b, 2,
      ieee_bytes<double>(1.0, 2) + ieee_bytes<double>(2.0, 2) + ieee_bytes<double>(4.0, 2));  // 5
  file +=
      "    -1\n  2411\n         1         1         1        11\n"
      "   0.0000000000000000E+00   0.0000000000000000E+00   0.0000000000000000E+00\n"
      "    -1\n";  // 6: nodes
  Uff58Header spectrum;
  spectrum.function_type = "12";  // spectrum
  spectrum.count = "2";
  file += binary_uff58(spectrum, 1, "\n    -1\n");  // 7: 8 bytes
  return file;
}

TEST(UffFormat, ReadsTimeResponsesAmongOtherDatasetsAndSaysWhichItSkipped) {
  const TempDir dir;
  const std::string path = dir.file("mixed.unv");
  write_file(path, mixed_file());
  ASSERT_EQ(&format_for_file(path), &uff_format());
  const FileContents contents = uff_format().describe(path);
  ASSERT_EQ(contents.file_signals.size(), 2u);
  EXPECT_EQ(contents.file_signals[0].name, "base:1:+Z");
  EXPECT_EQ(contents.file_signals[0].properties["dataset"], 4);
  EXPECT_EQ(contents.file_signals[1].name, "mass:2:+Z");
  EXPECT_EQ(contents.file_signals[1].properties["storage"]["byte_order"], "big-endian");
  EXPECT_EQ(contents.properties["datasets"], 7);
  const nlohmann::json& skipped = contents.properties["skipped_datasets"];
  ASSERT_EQ(skipped.size(), 5u);
  EXPECT_EQ(skipped[0]["dataset"], 1);
  EXPECT_EQ(skipped[0]["type"], "151");
  EXPECT_EQ(skipped[0]["reason"], "header, not dataset 58");
  EXPECT_EQ(skipped[1]["type"], "164");
  EXPECT_EQ(skipped[2]["dataset"], 3);
  EXPECT_EQ(skipped[2]["reason"],
            "function type 4 (frequency response function), not a time response");
  EXPECT_EQ(skipped[3]["type"], "2411");
  EXPECT_EQ(skipped[4]["dataset"], 7);
  EXPECT_EQ(skipped[4]["type"], "58b");
  EXPECT_EQ(contents.container,
            "UFF 58 and 58b, big-endian, 2 time responses, 5 other datasets skipped");

  Sidecar sidecar = volts_sidecar(1000.0, "base:1:+Z");
  sidecar.channels.push_back(channel("y", ChannelRole::Mass, Quantity::Displacement, "mm"));
  sidecar.channels[1].source = "dataset 5";  // the alias of "mass:2:+Z"
  const Recording recording = read_recording(path, sidecar);
  EXPECT_EQ(column(recording, 0), (std::vector<double>{0.25, -0.5, 0.75}));
  EXPECT_EQ(column(recording, 1), (std::vector<double>{1e-3, 2e-3, 4e-3}));
}

TEST(UffFormat, NamesSignalsThatShareADofByTheirDataset) {
  Uff58Header h;
  h.count = "1";
  const std::string file = ascii_uff58(h, e13_lines({1.0})) + ascii_uff58(h, e13_lines({2.0}));
  const TempDir dir;
  write_file(dir.file("twice.uff"), file);
  const FileContents contents = uff_format().describe(dir.file("twice.uff"));
  ASSERT_EQ(contents.file_signals.size(), 2u);
  EXPECT_EQ(contents.file_signals[0].name, "dataset 1");
  EXPECT_EQ(contents.file_signals[1].name, "dataset 2");
  const Recording recording =
      read_recording(dir.file("twice.uff"), volts_sidecar(1000.0, "dataset 2"));
  EXPECT_EQ(column(recording, 0), (std::vector<double>{2.0}));
  EXPECT_NE(input_error_of(
                [&] { read_recording(dir.file("twice.uff"), volts_sidecar(1000.0, "mic:3:-Y")); })
                .find("twice.uff: channel \"p\" of the sidecar given reads \"mic:3:-Y\", which the "
                      "file does not hold (it holds \"dataset 1\", \"dataset 2\""),
            std::string::npos);
}

TEST(UffFormat, ToleratesTouchingFieldsDExponentsLettersDroppedAndWideFields) {
  Uff58Header h;
  h.count = "9";
  h.eol = "\r\n";
  h.increment = "1.0D-3";  // a D exponent in record 7
  const std::string lines =
      " -1.50000E-02-2.50000E+002 3.00000E-005\r\n"  // fields that touch, 3-digit exponents
      "  1.00000D+00  1.23456-100 +4.00000E+00\r\n"  // D exponent, E dropped, a plus sign
      "   5.000000000000000000E-01   -6.0   7\r\n";  // wider fields, free format
  const TempDir dir;
  write_file(dir.file("t.uff"), ascii_uff58(h, lines));
  const FileContents contents = uff_format().describe(dir.file("t.uff"));
  ASSERT_EQ(contents.file_signals.size(), 1u);
  EXPECT_EQ(*contents.file_signals[0].sample_rate_hz, 1000.0);
  const std::vector<double> values =
      uff_signals().read_signal(dir.file("t.uff"), contents.file_signals[0], -1);
  EXPECT_EQ(values,
            (std::vector<double>{-1.5e-2, -2.5e2, 3e-5, 1.0, 1.23456e-100, 4.0, 0.5, -6.0, 7.0}));
}

TEST(UffFormat, ReadsAnAbscissaInMillisecondsAndKeepsAnIncrementThatIsNoWholeRate) {
  Uff58Header h;
  h.count = "1";
  h.increment = "2.50000E-01";  // ms: 4 kHz
  h.abscissa_units = "ms";
  Uff58Header g = h;
  g.response_node = "4";
  g.abscissa_units = "s";
  g.increment = "1.63840E-03";  // 610.3515625 Hz, no whole rate within its rounding
  const TempDir dir;
  write_file(dir.file("ms.uff"),
             ascii_uff58(h, e13_lines({1.0})) + ascii_uff58(g, e13_lines({2.0})));
  const FileContents contents = uff_format().describe(dir.file("ms.uff"));
  ASSERT_EQ(contents.file_signals.size(), 2u);
  EXPECT_DOUBLE_EQ(*contents.file_signals[0].sample_rate_hz, 4000.0);
  EXPECT_DOUBLE_EQ(*contents.file_signals[1].sample_rate_hz, 1.0 / 1.6384e-3);
}

// A time response as a Data Translation DT9837 writes it: abscissa units "(Sec)" and the values
// in fixed 13-character fields (6 to a line, format 6E13.6) with no space between them when
// the sign takes the field's first column.
TEST(UffFormat, ReadsADt9837TimeResponseWithItsUnitInParenthesesAndTouchingFields) {
  Uff58Header h;
  h.count = "8";                // record 7 field 2: 8 values
  h.increment = "9.76563E-05";  // record 7 field 5: 10.24 kHz
  h.abscissa_units = "(Sec)";   // record 8 field 6, as the DT9837 spells it
  h.ordinate_type = "2";        // record 7 field 1: real single precision
  const std::string lines =
      "-1.234567E-01-2.500000E+00 3.000000E-05-4.000000E-01 5.000000E+00-6.000000E-02\n"  // 6 × 13
      " 7.000000E+00-8.000000E-03\n";  // the last line: 2 × 13
  const TempDir dir;
  write_file(dir.file("dt9837.uff"), ascii_uff58(h, lines));
  const FileContents contents = uff_format().describe(dir.file("dt9837.uff"));
  ASSERT_EQ(contents.file_signals.size(), 1u);
  EXPECT_NEAR(*contents.file_signals[0].sample_rate_hz, 10240.0, 0.5);
  const std::vector<double> values =
      uff_signals().read_signal(dir.file("dt9837.uff"), contents.file_signals[0], -1);
  EXPECT_EQ(values, (std::vector<double>{-0.1234567, -2.5, 3e-5, -0.4, 5.0, -0.06, 7.0, -8e-3}));
}

// The spellings of seconds and milliseconds instruments write; a unit that is no time refused.
TEST(UffFormat, ReadsTheAbscissaUnitsInstrumentsSpellForSecondsAndMilliseconds) {
  const TempDir dir;
  for (const char* units : {"s", "S", "Sec", "sec", "SEC", "(Sec)", "Seconds", "second", "[s]",
                            "ms", "(ms)", "Milliseconds", "msec"}) {
    Uff58Header h;
    h.count = "1";
    h.abscissa_units = units;
    h.increment = "1.00000E-03";  // 1 kHz in s, 1 MHz in ms
    write_file(dir.file("u.uff"), ascii_uff58(h, e13_lines({1.0})));
    const FileContents contents = uff_format().describe(dir.file("u.uff"));
    ASSERT_EQ(contents.file_signals.size(), 1u) << units;
    const bool ms = std::string(units).find_first_of("mM") != std::string::npos;
    EXPECT_DOUBLE_EQ(*contents.file_signals[0].sample_rate_hz, ms ? 1e6 : 1e3) << units;
  }
  Uff58Header hz;
  hz.count = "1";
  hz.abscissa_units = "(Hz)";
  write_file(dir.file("hz.uff"), ascii_uff58(hz, e13_lines({1.0})));
  EXPECT_NE(input_error_of([&] {
              uff_format().describe(dir.file("hz.uff"));
            }).find("abscissa units \"(Hz)\" are not a time unit"),
            std::string::npos);
}

TEST(UffFormat, MatchesItsSignatureAndExtensions) {
  const FormatReader& uff = uff_format();
  EXPECT_TRUE(uff.matches_signature("    -1\n    58\n"));
  EXPECT_TRUE(uff.matches_signature("\n    -1\r\n    58b     1     2\r\n"));
  EXPECT_TRUE(uff.matches_signature("    -1                  \n   164\n"));
  EXPECT_FALSE(uff.matches_signature("-1\n58\n"));  // a column of numbers
  EXPECT_FALSE(uff.matches_signature("    -1\n  58.5\n"));
  EXPECT_FALSE(uff.matches_signature("    -1\n    58"));  // no whole line yet
  EXPECT_FALSE(uff.matches_signature("RIFF"));
  EXPECT_TRUE(uff.matches_extension(".uff"));
  EXPECT_TRUE(uff.matches_extension(".unv"));
  EXPECT_FALSE(uff.matches_extension(".csv"));
}

// --- Round trip and the same values through CSV ---------------------------------------------

TEST(UffFormat, ReadsBackOscilabsOwnUff58Export) {
  const Recording written =
      testing::sine_recording(512.0, 1000,
                              {channel("table", ChannelRole::Base, Quantity::Acceleration, "m/s^2"),
                               channel("mass", ChannelRole::Mass, Quantity::Displacement, "m"),
                               channel("force", ChannelRole::Force, Quantity::Force, "N")});
  const TempDir dir;
  const std::string path = dir.file("run.uff");
  write_recording_uff58(written, path);
  const FileContents contents = uff_format().describe(path);
  ASSERT_EQ(contents.file_signals.size(), 3u);
  // The writer puts the base on node 1, the rest on node 2, all along +X.
  EXPECT_EQ(contents.file_signals[0].name, "table:1:+X");
  EXPECT_EQ(contents.file_signals[1].name, "mass:2:+X");
  EXPECT_EQ(contents.file_signals[2].name, "force:2:+X");
  EXPECT_EQ(contents.file_signals[0].unit, "m/s^2");
  EXPECT_EQ(contents.file_signals[0].stored_type, "text, real double");
  EXPECT_EQ(*contents.file_signals[0].sample_rate_hz, 512.0);
  EXPECT_EQ(contents.properties["skipped_datasets"][0]["type"], "164");

  Sidecar sidecar = written.sidecar;
  for (std::size_t c = 0; c < sidecar.channels.size(); ++c) {
    sidecar.channels[c].source = contents.file_signals[c].name;
  }
  const Recording read = read_recording(path, sidecar);
  ASSERT_EQ(read.sample_count(), 1000);
  // 12 significant digits: relative rounding ≤ 5e-12 of each value (amplitudes ≤ 1).
  EXPECT_LE((read.samples_si - written.samples_si).cwiseAbs().maxCoeff(), 5e-12);
}

TEST(UffFormat, ReachesTheSameSamplesAsACsvOfTheSameValues) {
  // Values with a short exact decimal form, so that CSV, E-format text and float64 all hold them
  // exactly: k / 1024 for k from the rounded sines.
  const int n = 64;
  std::vector<double> a(n), b(n);
  for (int i = 0; i < n; ++i) {
    a[i] = std::round(1000.0 * std::sin(0.3 * i)) / 1024.0;
    b[i] = std::round(700.0 * std::cos(0.7 * i)) / 1024.0;
  }
  const TempDir dir;
  std::string csv = "t_s,a,y\n";
  for (int i = 0; i < n; ++i) {
    char row[96];
    std::snprintf(row, sizeof row, "%.17g,%.17g,%.17g\n", i / 256.0, a[i], b[i]);
    csv += row;
  }
  write_file(dir.file("same.csv"), csv);

  Uff58Header ha;
  ha.response_entity = "a";
  ha.ordinate_type = "4";
  ha.count = std::to_string(n);
  ha.increment = "3.90625E-03";  // 256 Hz
  std::string ascii_a;
  for (int i = 0; i < n; ++i) {
    char field[32];
    std::snprintf(field, sizeof field, "%25.17E", a[i]);  // wider than E20.12: exact
    ascii_a += field;
    if (i % 4 == 3) ascii_a += "\n";
  }
  Uff58Header hb = ha;
  hb.response_entity = "y";
  std::string data_b;
  for (const double v : b) data_b += ieee_bytes<double>(v, 2);
  write_file(dir.file("same.uff"), ascii_uff58(ha, ascii_a) + binary_uff58(hb, 2, data_b));

  Sidecar sidecar;
  sidecar.sample_rate_hz = 256.0;
  sidecar.channels = {channel("a", ChannelRole::Base, Quantity::Acceleration, "g", 0.5, 0.25),
                      channel("y", ChannelRole::Mass, Quantity::Displacement, "mm", 2.0)};
  const Recording from_csv = read_recording(dir.file("same.csv"), sidecar);
  sidecar.channels[0].source = "a:3:-Y";
  sidecar.channels[1].source = "y:3:-Y";
  const Recording from_uff = read_recording(dir.file("same.uff"), sidecar);
  ASSERT_EQ(from_uff.sample_count(), n);
  EXPECT_EQ(from_uff.samples_si, from_csv.samples_si);  // bit for bit
  EXPECT_EQ(from_uff.samples_stored, from_csv.samples_stored);
}

// --- Refusals ---------------------------------------------------------------------------------

// The message of describe (and of reading through a sidecar) for a file with `text`.
std::string refusal(const std::string& text, const std::string& name = "bad.uff") {
  const TempDir dir;
  write_file(dir.file(name), text);
  const std::string message = input_error_of([&] { uff_format().describe(dir.file(name)); });
  EXPECT_EQ(input_error_of([&] { read_recording(dir.file(name), volts_sidecar(1000.0, "x")); }),
            message);
  const std::size_t at = message.find(name);
  return at == std::string::npos ? message : message.substr(at);
}

std::string read_refusal(const std::string& text) {
  const TempDir dir;
  write_file(dir.file("bad.uff"), text);
  const std::string message = input_error_of(
      [&] { read_recording(dir.file("bad.uff"), volts_sidecar(1000.0, "mic:3:-Y")); });
  const std::size_t at = message.find("bad.uff");
  return at == std::string::npos ? message : message.substr(at);
}

Uff58Header two_values() {
  Uff58Header h;
  h.count = "2";
  return h;
}

TEST(UffFormatRefuses, UnknownAndComplexOrdinateDataTypes) {
  Uff58Header h = two_values();
  h.ordinate_type = "3";
  EXPECT_EQ(refusal(ascii_uff58(h, e13_lines({1, 2}))),
            "bad.uff: dataset 1 (time response): record 7: unknown ordinate data type 3 (2, 4 "
            "real single/double, 5, 6 complex)");
  for (const char* complex : {"5", "6"}) {
    h.ordinate_type = complex;
    EXPECT_EQ(refusal(ascii_uff58(h, e13_lines({1, 2, 3, 4}))),
              std::string("bad.uff: dataset 1 (time response): record 7: ordinate data type ") +
                  complex + " is complex; a recording is real (2 single, 4 double precision)");
  }
}

TEST(UffFormatRefuses, ByteCountsBeyondTheFile) {
  const std::string data = ieee_bytes<float>(1.0F, 1) + ieee_bytes<float>(2.0F, 1);
  std::string file = binary_uff58(two_values(), 1, data, 4096);
  EXPECT_EQ(refusal(file),
            "bad.uff: dataset 1: the binary header announces 4096 bytes of data at byte " +
                std::to_string(file.find(data)) + ", beyond the end of the file (" +
                std::to_string(data.size() + 7) + " bytes remain)");
}

TEST(UffFormatRefuses, ByteOrderAndFloatingPointCodesItDoesNotKnow) {
  const std::string data = ieee_bytes<float>(1.0F, 1) + ieee_bytes<float>(2.0F, 1);
  EXPECT_EQ(refusal(binary_uff58(two_values(), 1, data, -1, "3")),
            "bad.uff: dataset 1 (line 2): binary header of 58b: byte ordering 3 is neither 1 "
            "(little-endian) nor 2 (big-endian)");
  EXPECT_NE(refusal(binary_uff58(two_values(), 1, data, -1, "0")).find("byte ordering 0 is "),
            std::string::npos);
  EXPECT_EQ(refusal(binary_uff58(two_values(), 1, data, -1, "", "1")),
            "bad.uff: dataset 1 (line 2): binary header of 58b: floating-point format 1 (DEC VMS) "
            "is not read; only 2 (IEEE 754) is");
  EXPECT_EQ(refusal(binary_uff58(two_values(), 1, data, -1, "", "2", "12")),
            "bad.uff: dataset 1 (line 2): binary header of 58b: 12 ASCII lines announced, dataset "
            "58 has 11");
  EXPECT_EQ(refusal(binary_uff58(two_values(), 1, data, -1, "x")),
            "bad.uff: dataset 1 (line 2): binary header of 58b: byte ordering is not an integer: "
            "\"x\"");
  EXPECT_EQ(refusal("    -1\n    58b     1     2\n"),
            "bad.uff: dataset 1 (line 2): the binary header of 58b needs byte ordering, "
            "floating-point format, number of ASCII lines and number of bytes; it has 2 fields");
}

TEST(UffFormatRefuses, CountsOfValuesTheFileDoesNotHold) {
  // Binary: record 7 says 3 float32 values, the header 8 bytes.
  Uff58Header h = two_values();
  h.count = "3";
  const std::string data = ieee_bytes<float>(1.0F, 1) + ieee_bytes<float>(2.0F, 1);
  EXPECT_EQ(
      refusal(binary_uff58(h, 1, data)),
      "bad.uff: dataset 1 (line 13): record 7 declares 3 values of 4 bytes, the binary header "
      "8 bytes of data");
  // A byte count that is not where the data end: the closing "-1" is not after them.
  const std::string shifted = binary_uff58(two_values(), 1, data + "abcd", 8);
  EXPECT_EQ(refusal(shifted), "bad.uff: dataset 1 (byte " +
                                  std::to_string(shifted.find(data) + data.size()) +
                                  "): after the 8 bytes of binary data the binary header "
                                  "announces, expected the closing \"    -1\", found \"abcd    "
                                  "-1\"");
  // ASCII: 5 values declared, 4 in the file; then 3 declared, 4 in the file.
  h.count = "5";
  EXPECT_EQ(read_refusal(ascii_uff58(h, e13_lines({1, 2, 3, 4}))),
            "bad.uff: dataset 1: record 7 declares 5 values, the dataset holds 4");
  h.count = "3";
  EXPECT_EQ(read_refusal(ascii_uff58(h, e13_lines({1, 2, 3, 4}))),
            "bad.uff: dataset 1, line 14: more values than the 3 record 7 declares");
  // More values than the text could ever hold: refused before anything is allocated.
  h.count = "2147483647";
  EXPECT_EQ(refusal(ascii_uff58(h, e13_lines({1, 2}))),
            "bad.uff: dataset 1: record 7 declares 2147483647 values, but its 27 bytes of text "
            "cannot hold them");
  h.count = "-4";
  EXPECT_EQ(refusal(ascii_uff58(h, "")),
            "bad.uff: dataset 1 (time response): record 7: negative number of data values -4");
}

TEST(UffFormatRefuses, UnevenSpacingAndAbscissasThatAreNoTimeStep) {
  Uff58Header h = two_values();
  h.spacing = "0";
  EXPECT_EQ(refusal(ascii_uff58(h, e13_lines({0, 1, 1e-3, 2}))),
            "bad.uff: dataset 1 (time response): record 7: uneven abscissa spacing (abscissa "
            "values stored with each value) is not read; a recording needs an even spacing (1)");
  h.spacing = "2";
  EXPECT_EQ(refusal(ascii_uff58(h, e13_lines({1, 2}))),
            "bad.uff: dataset 1 (time response): record 7: abscissa spacing 2 is neither 0 "
            "(uneven) nor 1 (even)");
  h = two_values();
  h.abscissa_units = "Hz";
  EXPECT_EQ(refusal(ascii_uff58(h, e13_lines({1, 2}))),
            "bad.uff: dataset 1 (time response): record 8: abscissa units \"Hz\" are not a time "
            "unit (s, ms)");
  for (const char* increment : {"0.00000E+00", "-1.0E-03", "NaN", "Inf", "1E-320"}) {
    h = two_values();
    h.increment = increment;
    EXPECT_NE(refusal(ascii_uff58(h, e13_lines({1, 2}))).find("record 7: abscissa increment "),
              std::string::npos)
        << increment;
  }
}

TEST(UffFormatRefuses, FilesWithoutATimeResponse) {
  Uff58Header frf = two_values();
  frf.function_type = "4";
  EXPECT_EQ(refusal(ascii_uff58(frf, e13_lines({1, 2, 3, 4}))),
            "bad.uff: no time response (dataset 58, function type 1) to read as a recording "
            "(dataset 1 58: function type 4 (frequency response function), not a time response)");
  EXPECT_EQ(refusal("    -1\n   164\n    -1\n"),
            "bad.uff: no time response (dataset 58, function type 1) to read as a recording "
            "(dataset 1 164: units, not dataset 58)");
  EXPECT_EQ(refusal(""),
            "bad.uff: no dataset (a universal file holds datasets between \"-1\" "
            "lines)");
}

TEST(UffFormatRefuses, MalformedStructureAndFields) {
  EXPECT_EQ(refusal("hello\n"),
            "bad.uff: line 1: expected the line \"    -1\" that opens a dataset, found \"hello\"");
  EXPECT_EQ(refusal("    -1\n  58.0\n"),
            "bad.uff: dataset 1 (line 2): expected a dataset number after the \"-1\" line, found "
            "\"58.0\"");
  const std::string full = ascii_uff58(two_values(), e13_lines({1, 2}));
  EXPECT_EQ(refusal(full.substr(0, full.find("25-NOV"))),
            "bad.uff: dataset 1: the file ends within the header, before record 3");
  EXPECT_EQ(refusal("    -1\n    58\nid\n    -1\n"),
            "bad.uff: dataset 1 (line 4): the dataset closes within its header, before record 2");
  Uff58Header h = two_values();
  h.response_node = "x3";
  EXPECT_EQ(refusal(ascii_uff58(h, e13_lines({1, 2}))),
            "bad.uff: dataset 1 (line 8): record 6, response node: not an integer: \"x3\"");
  h = two_values();
  h.abscissa_min = "zero";
  EXPECT_EQ(refusal(ascii_uff58(h, e13_lines({1, 2}))),
            "bad.uff: dataset 1 (line 9): record 7, abscissa minimum: not a number: "
            "\"zero\"");
  h = two_values();
  EXPECT_EQ(read_refusal(ascii_uff58(h, " 1.00000E+00 abc\n")),
            "bad.uff: dataset 1, line 14: not a finite number: \"abc\"");
  EXPECT_EQ(read_refusal(ascii_uff58(h, " 1.00000E+00 1E999\n")),
            "bad.uff: dataset 1, line 14: not a finite number: \"1E999\"");
  EXPECT_EQ(refusal(ascii_uff58(h, e13_lines({1, 2})) + "trailing text\n"),
            "bad.uff: line 16: expected the line \"    -1\" that opens a dataset, found "
            "\"trailing text\"");
}

}  // namespace
}  // namespace oscilab::daq
