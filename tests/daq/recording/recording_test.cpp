#include "daq/recording/recording.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "analysis/common/input_error.h"
#include "analysis/signal/ac_coupling.h"
#include "tests/daq/recording/recording_test_util.h"

namespace oscilab::daq {
namespace {

using testing::channel;
using testing::input_error_of;
using testing::TempDir;

// Three channels in SI units, scale 1, offset 0: the stored values are the SI values.
std::vector<ChannelInfo> si_channels() {
  return {channel("base_acc", ChannelRole::Base, Quantity::Acceleration, "m/s^2"),
          channel("y", ChannelRole::Mass, Quantity::Displacement, "m"),
          channel("f", ChannelRole::Force, Quantity::Force, "N")};
}

// Channels in other units with a calibration, as sensors give them.
std::vector<ChannelInfo> calibrated_channels() {
  return {channel("base_acc", ChannelRole::Base, Quantity::Acceleration, "g", 0.5, 0.01),
          channel("y_dot", ChannelRole::Mass, Quantity::Velocity, "mm/s", 2.0, -0.3),
          channel("z", ChannelRole::Relative, Quantity::Displacement, "um", 1.5, 0.0),
          channel("f", ChannelRole::Force, Quantity::Force, "kN", 1e-3, 0.0)};
}

std::size_t files_in(const TempDir& dir) {
  return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(dir.path()),
                                                std::filesystem::directory_iterator()));
}

TEST(RecordingRoundTrip, Float64ContainersReturnSiUnitSamplesBitForBit) {
  const TempDir dir;
  const Recording written = testing::sine_recording(512.0, 1000, si_channels());
  for (const std::string name : {"run.wav", "run.w64", "run.rf64", "run.aiff", "run.caf"}) {
    SCOPED_TRACE(name);
    write_recording(written, dir.file(name));
    const Recording read = read_recording(dir.file(name));
    ASSERT_EQ(read.samples_si.rows(), written.samples_si.rows());
    ASSERT_EQ(read.samples_si.cols(), written.samples_si.cols());
    EXPECT_TRUE(read.samples_si == written.samples_si);  // float64: exact
    EXPECT_EQ(read.sidecar.sample_rate_hz, 512.0);
    EXPECT_EQ(sidecar_to_json(read.sidecar), sidecar_to_json(written.sidecar));
    EXPECT_EQ(read.source_path, dir.file(name));
    EXPECT_NE(read.container.find("64 bit float"), std::string::npos) << read.container;
  }
}

TEST(RecordingRoundTrip, CalibratedChannelsReturnTheSameSiSamplesToRounding) {
  const TempDir dir;
  const Recording written = testing::sine_recording(2048.0, 700, calibrated_channels());
  for (const std::string name : {"run.wav", "run.w64", "run.csv"}) {
    SCOPED_TRACE(name);
    write_recording(written, dir.file(name));
    const Recording read = read_recording(dir.file(name));
    ASSERT_EQ(read.samples_si.rows(), 700);
    // SI → stored → SI applies a division and a multiplication by the same factors: a few ulps
    // of the largest magnitude involved (the offset term) at most.
    for (Eigen::Index c = 0; c < read.samples_si.cols(); ++c) {
      const ChannelInfo& info = written.sidecar.channels[c];
      const double factor = unit_to_si(info.unit, info.quantity, "");
      const double magnitude =
          written.samples_si.col(c).cwiseAbs().maxCoeff() + std::abs(info.offset * factor);
      EXPECT_LE((read.samples_si.col(c) - written.samples_si.col(c)).cwiseAbs().maxCoeff(),
                8.0 * magnitude * 2.2e-16)
          << info.name;
    }
  }
}

TEST(RecordingRoundTrip, FlacReturnsSamplesWithinHalfAStep) {
  const TempDir dir;
  // 24-bit counts: amplitude 1 m/s² at 1e-6 m/s² per count, 0.1 m at 1e-7 m per count (1 µm
  // steps would do for a rig; finer here to check the rounding, not the range).
  std::vector<ChannelInfo> channels = {
      channel("base_acc", ChannelRole::Base, Quantity::Acceleration, "m/s^2", 1e-6, 0.0),
      channel("y", ChannelRole::Mass, Quantity::Displacement, "mm", 1e-4, 0.02),
      channel("f", ChannelRole::Force, Quantity::Force, "N", 1e-7, 0.0)};
  const Recording written = testing::sine_recording(512.0, 2000, channels);
  write_recording(written, dir.file("run.flac"));
  const Recording read = read_recording(dir.file("run.flac"));
  ASSERT_EQ(read.samples_si.rows(), 2000);
  EXPECT_NE(read.container.find("FLAC"), std::string::npos) << read.container;
  for (Eigen::Index c = 0; c < 3; ++c) {
    const ChannelInfo& info = channels[c];
    const double step_si = info.scale * unit_to_si(info.unit, info.quantity, "");
    // Rounding to the nearest count: at most half a step, plus float rounding of the step.
    EXPECT_LE((read.samples_si.col(c) - written.samples_si.col(c)).cwiseAbs().maxCoeff(),
              0.5 * step_si * (1.0 + 1e-9))
        << info.name;
    // And not merely zero: the signal really went through 24-bit counts.
    EXPECT_GT((read.samples_si.col(c) - written.samples_si.col(c)).cwiseAbs().maxCoeff(),
              0.05 * step_si)
        << info.name;
  }
}

TEST(RecordingWriter, ThrowsInputErrorNamingTheChannelWhenFlacWouldOverflow) {
  const TempDir dir;
  // 1 m/s² at 1e-8 per count is 1e8 counts, beyond 2^23.
  const Recording written = testing::sine_recording(
      512.0, 100,
      {channel("y", ChannelRole::Mass, Quantity::Displacement, "m", 1e-6),
       channel("base_acc", ChannelRole::Base, Quantity::Acceleration, "m/s^2", 1e-8)});
  const std::string message = input_error_of([&] { write_recording(written, dir.file("r.flac")); });
  EXPECT_EQ(message.rfind(dir.file("r.flac") + ": channel \"base_acc\": sample ", 0), 0u)
      << message;
  EXPECT_NE(message.find("24-bit"), std::string::npos) << message;
  EXPECT_EQ(files_in(dir), 0u);  // nothing written, no temporary left
}

TEST(RecordingRoundTrip, CsvWithHeaderIsExactAndStartsWithTimeColumn) {
  const TempDir dir;
  Recording written = testing::sine_recording(512.0, 300, si_channels());
  written.samples_si(7, 1) = 1.0 / 3.0;                 // needs all 17 digits
  written.samples_si(8, 1) = -4.9406564584124654e-324;  // subnormal
  write_recording(written, dir.file("run.csv"));
  const std::string text = testing::read_file(dir.file("run.csv"));
  EXPECT_EQ(text.rfind("t_s,base_acc,y,f\n0,", 0), 0u) << text.substr(0, 80);
  const Recording read = read_recording(dir.file("run.csv"));
  EXPECT_TRUE(read.samples_si == written.samples_si);
  EXPECT_EQ(read.container, "CSV, with header, delimiter \",\"");
}

// A file exported by another instrument: a title line, then time, the accelerometer's voltage
// (100 mV/g, 0.02 g offset after calibration), a temperature the analysis does not need, and a
// vibrometer's velocity in mm/s; semicolons; 2048 Hz. The sidecar maps the columns as they are.
TEST(CsvReader, ReadsAnotherInstrumentsHeaderlessFileThroughTheSidecarMapping) {
  const TempDir dir;
  const double rate_hz = 2048.0;
  const int rows = 600;
  std::string text = "time;voltage;temperature;velocity\r\n";
  std::vector<double> volts(rows);
  std::vector<double> velocity_mm_s(rows);
  for (int i = 0; i < rows; ++i) {
    volts[i] = 0.1 * std::sin(0.05 * i);
    velocity_mm_s[i] = 12.5 * std::cos(0.03 * i);
    char line[160];
    // Time printed to 6 decimals (0.5 µs rounding, far below half a sample, 244 µs).
    std::snprintf(line, sizeof line, "%.6f; %.9f;21.5;%.9f\r\n", i / rate_hz, volts[i],
                  velocity_mm_s[i]);
    text += line;
  }
  testing::write_file(dir.file("scope.csv"), text);
  testing::write_file(dir.file("scope.json"), R"({
    "sample_rate_hz": 2048,
    "csv": {"header": false, "delimiter": ";", "skip_lines": 1, "time_column": 0},
    "channels": [
      {"name": "base_acc", "role": "base", "quantity": "acceleration", "unit": "g",
       "scale": 10.0, "offset": 0.02, "column": 1, "sensor": "accelerometer, 100 mV/g"},
      {"name": "y_dot", "role": "mass", "quantity": "velocity", "unit": "mm/s",
       "scale": 1.0, "column": 3, "sensor": "laser vibrometer"}
    ]
  })");
  const Recording read = read_recording(dir.file("scope.csv"));
  ASSERT_EQ(read.samples_si.rows(), rows);
  ASSERT_EQ(read.samples_si.cols(), 2);
  EXPECT_DOUBLE_EQ(read.duration_s(), rows / rate_hz);
  for (int i = 0; i < rows; ++i) {
    // Printed with 9 decimals: the values are those to 5e-10 of their unit.
    const double base_acc_m_s2 = (10.0 * volts[i] + 0.02) * 9.80665;
    EXPECT_NEAR(read.samples_si(i, 0), base_acc_m_s2, 10.0 * 5e-10 * 9.80665 * 1.01);
    EXPECT_NEAR(read.samples_si(i, 1), velocity_mm_s[i] * 1e-3, 5e-10 * 1e-3 * 1.01);
  }
  EXPECT_EQ(read.container, "CSV, without header, delimiter \";\"");
}

TEST(CsvReader, SplitsOnRunsOfBlanksWhenTheDelimiterIsASpace) {
  const TempDir dir;
  testing::write_file(dir.file("s.txt"), "  1.5   -2\t 7\n\n2.5 -3 8   \n");
  testing::write_file(dir.file("s.json"), R"({"sample_rate_hz": 10,
    "csv": {"header": false, "delimiter": " "},
    "channels": [{"name": "f", "role": "force", "quantity": "force", "unit": "N", "scale": 2,
                  "column": 2}]})");
  const Recording read = read_recording(dir.file("s.txt"));
  ASSERT_EQ(read.samples_si.rows(), 2);
  EXPECT_EQ(read.samples_si(0, 0), 14.0);
  EXPECT_EQ(read.samples_si(1, 0), 16.0);
}

TEST(CsvReader, ReadsWithASidecarGivenInMemory) {
  const TempDir dir;
  testing::write_file(dir.file("bare.csv"), "t_s,y\n0,1\n0.5,2\n1,3\n");
  Sidecar sidecar;
  sidecar.sample_rate_hz = 2.0;
  sidecar.channels = {channel("y", ChannelRole::Mass, Quantity::Displacement, "mm")};
  const Recording read = read_recording(dir.file("bare.csv"), sidecar);
  ASSERT_EQ(read.samples_si.rows(), 3);
  EXPECT_EQ(read.samples_si(2, 0), 3e-3);
}

// Integer containers hold counts; `scale` turns a count into the unit. The file is written by
// hand from the WAV specification, not by the code under test.
TEST(SoundReader, ReadsIntegerPcmAsCountsTimesScale) {
  const TempDir dir;
  testing::write_file(dir.file("pcm.wav"),
                      testing::pcm16_wav(1000, 2, {0, 1000, -32768, 32767, 12, -12}));
  testing::write_file(dir.file("pcm.json"), R"({"sample_rate_hz": 1000, "channels": [
    {"name": "base_acc", "role": "base", "quantity": "acceleration", "unit": "V", "scale": 0.001},
    {"name": "y", "role": "mass", "quantity": "displacement", "unit": "um", "scale": 2,
     "offset": 1}]})");
  const Recording read = read_recording(dir.file("pcm.wav"));
  ASSERT_EQ(read.samples_si.rows(), 3);
  EXPECT_DOUBLE_EQ(read.samples_si(0, 0), 0.0);
  EXPECT_DOUBLE_EQ(read.samples_si(1, 0), -32.768);
  EXPECT_DOUBLE_EQ(read.samples_si(2, 0), 0.012);
  EXPECT_DOUBLE_EQ(read.samples_si(0, 1), (2.0 * 1000 + 1) * 1e-6);
  EXPECT_DOUBLE_EQ(read.samples_si(1, 1), (2.0 * 32767 + 1) * 1e-6);
  EXPECT_DOUBLE_EQ(read.samples_si(2, 1), (2.0 * -12 + 1) * 1e-6);
  EXPECT_NE(read.container.find("16 bit"), std::string::npos) << read.container;
}

TEST(SoundReader, AcceptsAFractionalSidecarRateThatRoundsToTheContainers) {
  const TempDir dir;
  const Recording written = testing::sine_recording(511.98, 50, si_channels());
  write_recording(written, dir.file("clock.wav"));
  const Recording read = read_recording(dir.file("clock.wav"));
  EXPECT_EQ(read.sidecar.sample_rate_hz, 511.98);  // the measured clock, kept
  EXPECT_DOUBLE_EQ(read.duration_s(), 50 / 511.98);
}

TEST(Recording, FindsChannelsByRoleAndName) {
  const Recording recording = testing::sine_recording(512.0, 10, calibrated_channels());
  EXPECT_EQ(recording.channel_index(ChannelRole::Mass), 1);
  EXPECT_EQ(recording.channel_index(ChannelRole::Force), 3);
  EXPECT_EQ(recording.channel_index("z"), 2);
  EXPECT_EQ(recording.channel_index("nope"), -1);
  Recording base_only = testing::sine_recording(
      512.0, 10, {channel("b", ChannelRole::Base, Quantity::Acceleration, "g")});
  EXPECT_EQ(base_only.channel_index(ChannelRole::Force), -1);
  EXPECT_DOUBLE_EQ(base_only.duration_s(), 10.0 / 512.0);
}

TEST(RecordingWriter, LeavesExactlyTheRecordingAndItsSidecar) {
  const TempDir dir;
  write_recording(testing::sine_recording(512.0, 64, si_channels()), dir.file("run.wav"));
  EXPECT_EQ(files_in(dir), 2u);
  EXPECT_TRUE(std::filesystem::exists(dir.file("run.json")));
}

TEST(RecordingWriter, FailedWriteLeavesTheExistingRecordingIntact) {
  const TempDir dir;
  Recording recording = testing::sine_recording(512.0, 64, si_channels());
  write_recording(recording, dir.file("run.wav"));
  const std::string wav = testing::read_file(dir.file("run.wav"));
  const std::string json = testing::read_file(dir.file("run.json"));
  recording.samples_si(10, 2) = std::nan("");
  const std::string message =
      input_error_of([&] { write_recording(recording, dir.file("run.wav")); });
  EXPECT_EQ(message,
            dir.file("run.wav") + ": channel \"f\": sample 10 (t = 0.0195312 s) is not finite");
  EXPECT_EQ(testing::read_file(dir.file("run.wav")), wav);
  EXPECT_EQ(testing::read_file(dir.file("run.json")), json);
  EXPECT_EQ(files_in(dir), 2u);
}

TEST(RecordingWriter, ThrowsInputErrorForUnknownContainerOrMismatchedShape) {
  const TempDir dir;
  Recording recording = testing::sine_recording(512.0, 8, si_channels());
  EXPECT_EQ(input_error_of([&] {
              write_recording(recording, dir.file("run.mp4"));
            }).rfind(dir.file("run.mp4") + ": unknown container \".mp4\"", 0),
            0u);
  recording.sidecar.channels.pop_back();
  EXPECT_EQ(input_error_of([&] { write_recording(recording, dir.file("run.wav")); }),
            dir.file("run.wav") +
                ": the recording holds 3 sample columns, its sidecar lists 2 "
                "channels");
  EXPECT_EQ(files_in(dir), 0u);
}

}  // namespace
}  // namespace oscilab::daq

namespace oscilab::daq {
namespace {

TEST(RecordingReader, UndoesTheAcCouplingOfAChannelThatStatesIt) {
  // A channel with ac_coupling_hz is calibrated, then passed through the inverse of its input's
  // high-pass (analysis/signal/ac_coupling.h, tested against the closed form there), sample by
  // sample as the live chain does; the other channels are left as they are.
  const testing::TempDir dir;
  Recording recording = testing::sine_recording(
      512.0, 4096,
      {testing::channel("b", ChannelRole::Base, Quantity::Acceleration, "m/s^2"),
       testing::channel("y", ChannelRole::Mass, Quantity::Displacement, "m")});
  recording.sidecar.channels[1].ac_coupling_hz = 2.0;
  const std::string path = dir.file("ac.wav");
  write_recording(recording, path);
  const Recording read = read_recording(path);
  analysis::AcCouplingInverse inverse(2.0, 512.0, "test");
  for (Eigen::Index r = 0; r < 4096; ++r) {
    ASSERT_EQ(read.samples_si(r, 0), recording.samples_si(r, 0));
    ASSERT_NEAR(read.samples_si(r, 1), inverse.push(recording.samples_si(r, 1)), 1e-12);
  }
}

}  // namespace
}  // namespace oscilab::daq
