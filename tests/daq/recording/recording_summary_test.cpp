#include "daq/recording/recording_summary.h"

#include <gtest/gtest.h>

#include <string>

#include "tests/daq/recording/recording_test_util.h"

namespace oscilab::daq {
namespace {

using testing::channel;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

Recording small_recording() {
  Recording recording;
  recording.sidecar.sample_rate_hz = 4.0;
  recording.sidecar.mass_kg = 0.26;
  ChannelInfo y = channel("y", ChannelRole::Mass, Quantity::Displacement, "mm", 1.0);
  y.sensor = "laser vibrometer";
  recording.sidecar.channels = {
      y, channel("base_acc", ChannelRole::Base, Quantity::Acceleration, "g", 0.5)};
  recording.samples_si.resize(4, 2);
  recording.samples_si.col(0) << 1e-3, -2e-3, 3e-3, -4e-3;  // rms = sqrt(30 / 4) mm
  recording.samples_si.col(1) << 0.0, 0.0, 0.0, 0.0;
  return recording;
}

TEST(DescribeRecording, ListsRateDurationAndEachChannelWithSiStatistics) {
  const std::string text = describe_recording(small_recording());
  EXPECT_TRUE(contains(text, "Recording: (in memory)\n")) << text;
  EXPECT_TRUE(contains(text, "sample rate:  4 Hz\n")) << text;
  EXPECT_TRUE(contains(text, "samples:      4\n")) << text;
  EXPECT_TRUE(contains(text, "duration:     1 s\n")) << text;
  EXPECT_TRUE(contains(text, "mass:         0.26 kg\n")) << text;
  EXPECT_TRUE(contains(text, "Channels (2):\n")) << text;
  EXPECT_TRUE(contains(text,
                       "1. y: role mass, displacement, unit in file mm (scale 1, offset 0), "
                       "sensor laser vibrometer\n"))
      << text;
  EXPECT_TRUE(contains(text, "min -0.004 m, max 0.003 m, rms 0.00273861 m\n")) << text;
  EXPECT_TRUE(contains(text, "2. base_acc: role base, acceleration, unit in file g (scale 0.5"))
      << text;
  EXPECT_TRUE(contains(text, "min 0 m/s^2, max 0 m/s^2, rms 0 m/s^2\n")) << text;
  EXPECT_TRUE(contains(text, "Excitation: none (the analysis will detect it)\n")) << text;
}

TEST(DescribeRecording, ListsTheExcitationLevelsAndTheirTimeSpans) {
  Recording recording = small_recording();
  Excitation excitation;
  excitation.type = "stepped-sine";
  excitation.frequency_hz = 9.0;
  excitation.levels = {{0.2, 0.0, 10.0, {}}, {0.6, 12.0, 22.0, {}}, {0.4, 24.0, 34.5, {}}};
  recording.sidecar.excitation = excitation;
  const std::string text = describe_recording(recording);
  EXPECT_TRUE(contains(text, "type:         stepped-sine\n")) << text;
  EXPECT_TRUE(contains(text, "frequency:    9 Hz\n")) << text;
  EXPECT_TRUE(contains(text, "levels:       3, f0 from 0.2 N to 0.6 N\n")) << text;
  EXPECT_TRUE(contains(text, "level 3: f0 = 0.4 N, 24 s to 34.5 s\n")) << text;
}

TEST(DescribeRecording, SaysWhatAPartialExcitationLeavesToTheAnalysis) {
  Recording recording = small_recording();
  recording.sidecar.excitation = Excitation{};
  const std::string text = describe_recording(recording);
  EXPECT_TRUE(contains(text, "type:         not given\n")) << text;
  EXPECT_TRUE(contains(text, "frequency:    not given (the analysis will detect it)\n")) << text;
  EXPECT_TRUE(contains(text, "levels:       not given (the analysis will detect them)\n")) << text;
}

TEST(DescribeRecording, NamesTheFileAndContainerOfARecordingRead) {
  const testing::TempDir dir;
  write_recording(small_recording(), dir.file("run.wav"));
  const std::string text = describe_recording(read_recording(dir.file("run.wav")));
  EXPECT_TRUE(contains(text, "Recording: " + dir.file("run.wav") + "\n")) << text;
  EXPECT_TRUE(contains(text, "container:    WAV")) << text;
}

}  // namespace
}  // namespace oscilab::daq
