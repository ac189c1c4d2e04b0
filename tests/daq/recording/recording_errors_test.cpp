// Every way a recording can be untrustworthy gives one InputError naming the file and the
// problem (contract §1, last point).
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <limits>
#include <string>

#include "analysis/common/input_error.h"
#include "daq/recording/measurement_mapping.h"
#include "daq/recording/recording.h"
#include "tests/daq/recording/recording_test_util.h"

namespace oscilab::daq {
namespace {

using testing::channel;
using testing::input_error_of;
using testing::TempDir;

std::vector<ChannelInfo> two_channels() {
  return {channel("base_acc", ChannelRole::Base, Quantity::Acceleration, "m/s^2"),
          channel("y", ChannelRole::Mass, Quantity::Displacement, "mm", 1.0)};
}

constexpr const char* kCsvSidecar = R"({"sample_rate_hz": 4, "channels": [
  {"name": "base_acc", "role": "base", "quantity": "acceleration", "unit": "m/s^2", "scale": 1},
  {"name": "y", "role": "mass", "quantity": "displacement", "unit": "mm", "scale": 1}]})";

// Writes `csv` as rec.csv with the two-channel sidecar (4 Hz) and returns the read error.
std::string csv_error(const TempDir& dir, const std::string& csv,
                      const std::string& sidecar = kCsvSidecar) {
  testing::write_file(dir.file("rec.csv"), csv);
  testing::write_file(dir.file("rec.json"), sidecar);
  return input_error_of([&] { read_recording(dir.file("rec.csv")); });
}

std::string read_error(const std::string& path) {
  return input_error_of([&] { read_recording(path); });
}

bool starts_with(const std::string& text, const std::string& start) {
  return text.rfind(start, 0) == 0;
}

TEST(RecordingReader, ThrowsInputErrorWhenSidecarIsMissing) {
  const TempDir dir;
  write_recording(testing::sine_recording(512.0, 16, two_channels()), dir.file("run1.wav"));
  std::filesystem::remove(dir.file("run1.json"));
  EXPECT_TRUE(
      starts_with(read_error(dir.file("run1.wav")),
                  dir.file("run1.wav") + ": sidecar " + dir.file("run1.json") + " not found"))
      << read_error(dir.file("run1.wav"));
}

TEST(RecordingReader, ThrowsInputErrorWhenSidecarIsMalformedJson) {
  const TempDir dir;
  write_recording(testing::sine_recording(512.0, 16, two_channels()), dir.file("run1.wav"));
  testing::write_file(dir.file("run1.json"), "{\"sample_rate_hz\": 512, \"channels\": [}");
  const std::string message = read_error(dir.file("run1.wav"));
  EXPECT_TRUE(starts_with(message, dir.file("run1.json") + ": malformed JSON: ")) << message;
  EXPECT_NE(message.find("line 1"), std::string::npos) << message;
}

TEST(RecordingReader, ThrowsInputErrorWhenSidecarFieldIsInvalid) {
  const TempDir dir;
  write_recording(testing::sine_recording(512.0, 16, two_channels()), dir.file("run1.wav"));
  std::string json = testing::read_file(dir.file("run1.json"));
  json.replace(json.find("\"mm\""), 4, "\"mps\"");
  testing::write_file(dir.file("run1.json"), json);
  EXPECT_TRUE(starts_with(read_error(dir.file("run1.wav")),
                          dir.file("run1.json") + ": channels[1].unit: unknown unit \"mps\""))
      << read_error(dir.file("run1.wav"));
}

TEST(RecordingReader, ThrowsInputErrorWhenChannelCountDiffersFromSidecar) {
  const TempDir dir;
  write_recording(testing::sine_recording(512.0, 16, two_channels()), dir.file("run1.wav"));
  Sidecar sidecar = read_sidecar(dir.file("run1.json"));
  sidecar.channels.push_back(channel("f", ChannelRole::Force, Quantity::Force, "N"));
  write_sidecar(sidecar, dir.file("run1.json"));
  EXPECT_EQ(
      read_error(dir.file("run1.wav")),
      dir.file("run1.wav") + ": the file holds 2 channels, " + dir.file("run1.json") + " lists 3");
}

TEST(RecordingReader, ThrowsInputErrorWhenSampleRateDiffersFromSidecar) {
  const TempDir dir;
  write_recording(testing::sine_recording(512.0, 16, two_channels()), dir.file("run1.flac"));
  Sidecar sidecar = read_sidecar(dir.file("run1.json"));
  sidecar.sample_rate_hz = 2048.0;
  write_sidecar(sidecar, dir.file("run1.json"));
  EXPECT_EQ(read_error(dir.file("run1.flac")), dir.file("run1.flac") +
                                                   ": the file's sample rate is 512 Hz, " +
                                                   dir.file("run1.json") + " says 2048 Hz");
}

TEST(RecordingReader, ThrowsInputErrorWhenSoundFileHasNoSamples) {
  const TempDir dir;
  testing::write_file(dir.file("empty.wav"), testing::pcm16_wav(512, 2, {}));
  testing::write_file(dir.file("empty.json"), kCsvSidecar);
  std::string json = kCsvSidecar;
  json.replace(json.find("4,"), 2, "512,");
  testing::write_file(dir.file("empty.json"), json);
  EXPECT_EQ(read_error(dir.file("empty.wav")),
            dir.file("empty.wav") + ": no samples (empty recording)");
}

TEST(RecordingReader, ThrowsInputErrorWhenFileIsEmptyOrNotASoundFile) {
  const TempDir dir;
  testing::write_file(dir.file("zero.wav"), "");
  testing::write_file(dir.file("zero.json"), kCsvSidecar);
  EXPECT_TRUE(starts_with(read_error(dir.file("zero.wav")),
                          dir.file("zero.wav") + ": not a sound file libsndfile can read ("))
      << read_error(dir.file("zero.wav"));
  testing::write_file(dir.file("text.wav"), "t_s,base_acc,y\n0,1,2\n");
  testing::write_file(dir.file("text.json"), kCsvSidecar);
  EXPECT_TRUE(starts_with(read_error(dir.file("text.wav")),
                          dir.file("text.wav") + ": not a sound file libsndfile can read ("))
      << read_error(dir.file("text.wav"));
}

TEST(RecordingReader, ThrowsInputErrorWhenSoundFileIsTruncated) {
  const TempDir dir;
  write_recording(testing::sine_recording(512.0, 400, two_channels()), dir.file("cut.wav"));
  const std::string bytes = testing::read_file(dir.file("cut.wav"));
  testing::write_file(dir.file("cut.wav"), bytes.substr(0, bytes.size() - 1000));
  const std::string message = read_error(dir.file("cut.wav"));
  EXPECT_TRUE(starts_with(message, dir.file("cut.wav") + ": truncated: ")) << message;
}

TEST(RecordingReader, ThrowsInputErrorNamingChannelAndSampleOfANanInASoundFile) {
  const TempDir dir;
  write_recording(testing::sine_recording(512.0, 100, two_channels()), dir.file("nan.wav"));
  std::string bytes = testing::read_file(dir.file("nan.wav"));
  const std::size_t data = bytes.find("data", 12) + 8;  // float64 samples, interleaved
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  std::memcpy(&bytes[data + 8 * (2 * 37 + 1)], &nan, sizeof nan);  // sample 37 of channel "y"
  std::memcpy(&bytes[data + 8 * (2 * 38 + 1)], &inf, sizeof inf);
  testing::write_file(dir.file("nan.wav"), bytes);
  EXPECT_EQ(read_error(dir.file("nan.wav")),
            dir.file("nan.wav") +
                ": channel \"y\": sample 37 (t = 0.0722656 s) is NaN; 2 of 100 samples of this "
                "channel are not finite");
}

TEST(RecordingReader, ThrowsInputErrorWhenDataFileIsMissingOrUnreadable) {
  const TempDir dir;
  EXPECT_EQ(read_error(dir.file("none.wav")), dir.file("none.wav") + ": file not found");
  std::filesystem::create_directory(dir.file("folder.wav"));
  testing::write_file(dir.file("folder.json"), kCsvSidecar);
  EXPECT_EQ(read_error(dir.file("folder.wav")),
            dir.file("folder.wav") + ": cannot read: not a regular file");
}

TEST(CsvReader, ThrowsInputErrorWhenFileIsEmpty) {
  const TempDir dir;
  EXPECT_EQ(csv_error(dir, ""), dir.file("rec.csv") + ": no samples (empty file: no header line)");
  EXPECT_EQ(csv_error(dir, "t_s,base_acc,y\n\n"),
            dir.file("rec.csv") + ": no samples (the file holds no data rows)");
}

TEST(CsvReader, ThrowsInputErrorNamingTheLineOfATruncatedRow) {
  const TempDir dir;
  EXPECT_EQ(csv_error(dir, "t_s,base_acc,y\n0,1,2\n0.25,3,4\n0.5,5"),
            dir.file("rec.csv") +
                ": line 4: expected 3 columns, found 2 (truncated or "
                "malformed row)");
}

TEST(CsvReader, ThrowsInputErrorNamingLineAndColumnOfANonNumericCell) {
  const TempDir dir;
  EXPECT_EQ(csv_error(dir, "t_s,base_acc,y\n0,1,2\n0.25,3,4x\n"),
            dir.file("rec.csv") + ": line 3, column 3 (channel \"y\"): not a number: \"4x\"");
  EXPECT_EQ(csv_error(dir, "t_s,base_acc,y\n0,1,2\n0.25,,4\n"),
            dir.file("rec.csv") + ": line 3, column 2 (channel \"base_acc\"): empty cell");
  EXPECT_EQ(csv_error(dir, "t_s,base_acc,y\n0,1,2\n0.25,1e999,4\n"),
            dir.file("rec.csv") +
                ": line 3, column 2 (channel \"base_acc\"): number out of range: \"1e999\"");
}

TEST(CsvReader, ThrowsInputErrorNamingChannelSampleAndLineOfNanOrInf) {
  const TempDir dir;
  EXPECT_EQ(csv_error(dir, "t_s,base_acc,y\n0,1,2\n0.25,3,4\n0.5,nan,6\n0.75,inf,8\n"),
            dir.file("rec.csv") +
                ": channel \"base_acc\": sample 2 (t = 0.5 s, line 4) is NaN; 2 of 4 samples of "
                "this channel are not finite");
  EXPECT_EQ(csv_error(dir, "base_acc,y\n1,-inf\n"),
            dir.file("rec.csv") +
                ": channel \"y\": sample 0 (t = 0 s, line 2) is infinite; 1 of 1 samples of this "
                "channel are not finite");
}

TEST(CsvReader, ThrowsInputErrorWhenCalibrationOverflows) {
  const TempDir dir;
  std::string sidecar = kCsvSidecar;
  sidecar.replace(sidecar.find("\"scale\": 1}"), 11, "\"scale\": 1e12}");
  EXPECT_EQ(csv_error(dir, "base_acc,y\n1,2\n1e300,3\n", sidecar),
            dir.file("rec.csv") +
                ": channel \"base_acc\": sample 1 (t = 0.25 s, line 3) (1e+300) overflows after "
                "calibration (scale 1e+12); 1 of 2 samples of this channel are not finite");
}

TEST(CsvReader, ThrowsInputErrorNamingTheLineWhereTimeDoesNotIncrease) {
  const TempDir dir;
  EXPECT_EQ(csv_error(dir, "t_s,base_acc,y\n0,1,2\n0.25,3,4\n0.25,5,6\n"),
            dir.file("rec.csv") +
                ": line 4, column 1 (time): time 0.25 s does not increase (previous 0.25 s)");
}

TEST(CsvReader, ThrowsInputErrorNamingTheLineWhereTimeDisagreesWithTheRate) {
  const TempDir dir;
  // A skipped sample at line 5: 0.75 s follows 0.25 s at 4 Hz.
  EXPECT_EQ(csv_error(dir, "t_s,base_acc,y\n0,1,2\n0.25,3,4\n0.75,5,6\n"),
            dir.file("rec.csv") + ": line 4, column 1 (time): time 0.75 s does not fit " +
                dir.file("rec.json") + "'s sample_rate_hz 4 (sample 2 should be at 0.5 s)");
}

TEST(CsvReader, ThrowsInputErrorWhenHeaderLacksAChannel) {
  const TempDir dir;
  EXPECT_EQ(csv_error(dir, "t_s,base_acc,z\n0,1,2\n"),
            dir.file("rec.csv") + ": line 1: the header has no column \"y\" for that channel of " +
                dir.file("rec.json") + " (found \"t_s\", \"base_acc\", \"z\")");
}

TEST(CsvReader, ThrowsInputErrorSuggestingTheLayoutWhenTheHeaderIsMissing) {
  const TempDir dir;
  const std::string message = csv_error(dir, "0,1,2\n0.25,3,4\n");
  EXPECT_TRUE(
      starts_with(message, dir.file("rec.csv") + ": line 1: the header has no column \"base_acc\""))
      << message;
  EXPECT_NE(message.find("needs \"csv\": {\"header\": false}"), std::string::npos) << message;
}

TEST(CsvReader, ThrowsInputErrorNamingTheDataFileWhenTheGivenSidecarIsInvalid) {
  const TempDir dir;
  testing::write_file(dir.file("bare.csv"), "y\n1\n");
  Sidecar sidecar;
  sidecar.sample_rate_hz = 0.0;
  sidecar.channels = {channel("y", ChannelRole::Mass, Quantity::Displacement, "mm")};
  EXPECT_EQ(input_error_of([&] { read_recording(dir.file("bare.csv"), sidecar); }),
            dir.file("bare.csv") +
                ": the sidecar given: sample_rate_hz: expected a positive number, got 0.0");
}

TEST(CsvReader, ThrowsInputErrorWhenAMappedColumnIsBeyondTheRow) {
  const TempDir dir;
  const std::string sidecar = R"({"sample_rate_hz": 4, "csv": {"header": false},
    "channels": [{"name": "y", "role": "mass", "quantity": "displacement", "unit": "mm",
                  "scale": 1, "column": 4}]})";
  EXPECT_EQ(csv_error(dir, "0,1,2\n", sidecar),
            dir.file("rec.csv") +
                ": line 1: channel \"y\" reads column 4 (0-based), but there are only 3");
}

// The excitation frequency the analysis is given (sidecar or override) must leave whole cycles to
// fit: below Nyquist, and at least two cycles in the record. 10 s at 512 Hz in memory.
TEST(MeasurementMapping, RefusesAnExcitationFrequencyWithoutTwoCyclesBelowNyquist) {
  Recording recording;
  recording.source_path = "dir/run1.flac";
  recording.sidecar.sample_rate_hz = 512.0;
  recording.sidecar.channels = two_channels();
  recording.sidecar.excitation = Excitation{};
  recording.samples_si = Eigen::MatrixXd::Zero(5120, 2);
  const auto error_for = [&](double sidecar_hz, std::optional<double> override_hz) {
    recording.sidecar.excitation->frequency_hz = sidecar_hz;
    MappingOverrides overrides;
    overrides.excitation_freq_hz = override_hz;
    return input_error_of([&] { measurement_channels(recording, overrides); });
  };
  // A sidecar frequency is named by its field (the sidecar parser refuses Nyquist too; this is
  // the check the analysis relies on for recordings made in memory or read otherwise).
  EXPECT_EQ(error_for(0.1, std::nullopt),
            "dir/run1.json: excitation.frequency_hz: 0.1 Hz: the record's 10 s hold fewer than "
            "two of its cycles");
  EXPECT_EQ(error_for(1e-9, std::nullopt),
            "dir/run1.json: excitation.frequency_hz: 1e-09 Hz: the record's 10 s hold fewer "
            "than two of its cycles");
  EXPECT_EQ(error_for(300.0, std::nullopt),
            "dir/run1.json: excitation.frequency_hz: 300 Hz is not below the Nyquist frequency, "
            "256 Hz at 512 Hz sampling");
  // An override names itself, and is checked instead of the sidecar's value.
  EXPECT_EQ(error_for(9.0, 1e9),
            "dir/run1.flac: the excitation frequency given (--freq): 1e+09 Hz is not below the "
            "Nyquist frequency, 256 Hz at 512 Hz sampling");
  EXPECT_EQ(error_for(1e9, 9.0), "");  // the sidecar's value is replaced, not used
  // At the limits: two cycles exactly, and just below Nyquist, are accepted.
  EXPECT_EQ(error_for(0.2, std::nullopt), "");
  EXPECT_EQ(error_for(255.9, std::nullopt), "");
}

}  // namespace
}  // namespace oscilab::daq
