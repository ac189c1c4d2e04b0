#include "ui/review/cursor_readout.h"

#include <gtest/gtest.h>

namespace oscilab::ui {
namespace {

// Strings are moved in rather than assigned from literals: GCC 12 at -O3 warns falsely
// (-Wrestrict, GCC bug 105651) on short literal assignments to std::string.
daq::ChannelInfo channel(std::string name, daq::Quantity quantity) {
  daq::ChannelInfo info;
  info.name = std::move(name);
  info.quantity = quantity;
  return info;
}

daq::OpenedRecording ramp_recording() {
  daq::Recording recording;
  recording.sidecar.sample_rate_hz = 512.0;
  recording.sidecar.channels = {channel("base_acc", daq::Quantity::Acceleration),
                                channel("y", daq::Quantity::Displacement)};
  recording.samples_si.resize(1024, 2);
  for (Eigen::Index i = 0; i < 1024; ++i) {
    recording.samples_si(i, 0) = double(i);          // m/s²: the sample index
    recording.samples_si(i, 1) = -1e-3 * double(i);  // m: −index mm
  }
  return daq::hold_recording(std::move(recording));
}

TEST(CursorReadout, SnapsToTheNearestSample) {
  const daq::OpenedRecording recording = ramp_recording();
  // 1.0 s + 0.4 sample → sample 512; + 0.6 sample → sample 513.
  const CursorReadout below = read_cursor(recording, 1.0 + 0.4 / 512.0);
  EXPECT_EQ(below.sample, 512);
  EXPECT_DOUBLE_EQ(below.t_s, 1.0);
  ASSERT_EQ(below.values_si.size(), 2u);
  EXPECT_DOUBLE_EQ(below.values_si[0], 512.0);
  EXPECT_DOUBLE_EQ(below.values_si[1], -0.512);
  EXPECT_EQ(read_cursor(recording, 1.0 + 0.6 / 512.0).sample, 513);
}

TEST(CursorReadout, ClampsToTheRecording) {
  const daq::OpenedRecording recording = ramp_recording();
  EXPECT_EQ(read_cursor(recording, -5.0).sample, 0);
  EXPECT_EQ(read_cursor(recording, 1e6).sample, 1023);
  EXPECT_DOUBLE_EQ(read_cursor(recording, 1e6).t_s, 1023.0 / 512.0);
}

TEST(CursorReadout, IsEmptyWithoutSamples) {
  daq::Recording none;
  none.sidecar = ramp_recording().sidecar;
  none.samples_si.resize(0, 2);
  const daq::OpenedRecording recording = daq::hold_recording(none);
  EXPECT_EQ(read_cursor(recording, 0.0).sample, -1);
  EXPECT_EQ(format_readout(read_cursor(recording, 0.0), recording, {}), "");
}

TEST(CursorReadout, FormatsTimeToTheSamplingResolutionAndValuesInDisplayUnits) {
  const daq::OpenedRecording recording = ramp_recording();
  const std::vector<DisplayUnit> units = {{"m/s²", 1.0, 0}, {"mm", 1e-3, 1}};
  // Widths: 4 digits and a sign for base_acc ("-1023"), 3 + 1 decimal and a sign for y.
  EXPECT_EQ(format_readout(read_cursor(recording, 1.0), recording, units),
            "t = 1.000 s   base_acc =   512 m/s²   y = -512.0 mm");
  EXPECT_EQ(format_readout(read_cursor(recording, 2.0 / 512), recording, units),
            "t = 0.004 s   base_acc =     2 m/s²   y =   -2.0 mm");
}

}  // namespace
}  // namespace oscilab::ui
