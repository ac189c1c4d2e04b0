#include "daq/live/stream_calibration.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "tests/daq/stream_test_layout.h"

namespace oscilab::daq {
namespace {

RawBlock block_of(std::vector<double> values, int channels) {
  RawBlock block;
  block.channels = channels;
  block.rows = static_cast<int>(values.size()) / channels;
  block.values = std::move(values);
  return block;
}

TEST(StreamCalibration, CalibratesStoredValuesToSiAndTheForceFromTheBaseAcceleration) {
  Sidecar layout = testing::two_channel_layout();  // base: 3e-5 m/s² per count; y: 1e-7 m
  layout.channels[1].unit = "mm";
  layout.channels[1].scale = 2.0;
  layout.channels[1].offset = 1.0;
  StreamCalibration calibration(layout);
  ASSERT_TRUE(calibration.analysed());
  EXPECT_FALSE(calibration.mass_relative());
  EXPECT_EQ(calibration.mass_kg(), 0.26);
  StreamCalibration::Rows rows = calibration.make_rows(4);
  calibration.calibrate(block_of({1000.0, 3.0, -2000.0, 4.5}, 2), rows);
  // physical = (scale × stored + offset) × the unit's factor to SI.
  EXPECT_DOUBLE_EQ(rows.base_si[0], 3e-5 * 1000.0);
  EXPECT_DOUBLE_EQ(rows.base_si[1], 3e-5 * -2000.0);
  EXPECT_DOUBLE_EQ(rows.mass_si[0], (2.0 * 3.0 + 1.0) * 1e-3);
  EXPECT_DOUBLE_EQ(rows.mass_shown[1], (2.0 * 4.5 + 1.0) * 1e-3);
  EXPECT_DOUBLE_EQ(rows.force_n[0], -0.26 * 3e-5 * 1000.0);  // eq. (1): f = −m b̈
}

TEST(StreamCalibration, ABadSampleIsZeroForTheFiltersAndAHoleForTheDisplay) {
  StreamCalibration calibration(testing::two_channel_layout());
  StreamCalibration::Rows rows = calibration.make_rows(2);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  calibration.calibrate(block_of({nan, 1.0, 2.0, std::numeric_limits<double>::infinity()}, 2),
                        rows);
  EXPECT_EQ(rows.base_si[0], 0.0);
  EXPECT_TRUE(std::isnan(rows.base_shown[0]));
  EXPECT_TRUE(std::isnan(rows.force_n[0]));
  EXPECT_EQ(rows.mass_si[1], 0.0);
  EXPECT_TRUE(std::isnan(rows.mass_shown[1]));
  EXPECT_TRUE(std::isfinite(rows.force_n[1]));
}

TEST(StreamCalibration, TakesTheRelativeChannelWithoutAMassChannel) {
  Sidecar layout = testing::two_channel_layout();
  layout.channels[1].role = ChannelRole::Relative;
  StreamCalibration calibration(layout);
  EXPECT_TRUE(calibration.analysed());
  EXPECT_TRUE(calibration.mass_relative());
  EXPECT_EQ(calibration.mass().index, 1);
}

TEST(StreamCalibration, AnalysesNothingWithoutTwoMotionChannels) {
  Sidecar layout = testing::two_channel_layout();
  layout.channels[1].role = ChannelRole::Force;
  EXPECT_FALSE(StreamCalibration(layout).analysed());
  layout = testing::two_channel_layout();
  layout.channels[0].quantity = Quantity::Force;
  layout.channels[0].unit = "N";
  EXPECT_FALSE(StreamCalibration(layout).analysed());
  EXPECT_FALSE(StreamCalibration().analysed());
}

TEST(StreamCalibration, WarnsWhenTheExcitationIsWithinTenTimesAnAcCouplingCorner) {
  Sidecar layout = testing::two_channel_layout();
  layout.channels[1].ac_coupling_hz = 2.2;
  const StreamCalibration calibration(layout);
  const std::vector<std::string> near = calibration.ac_coupling_warnings(9.0);  // < 22 Hz
  ASSERT_EQ(near.size(), 1u);
  EXPECT_NE(near[0].find("channel \"y\""), std::string::npos) << near[0];
  EXPECT_NE(near[0].find("AC-coupling corner"), std::string::npos) << near[0];
  EXPECT_TRUE(calibration.ac_coupling_warnings(30.0).empty());
  EXPECT_TRUE(calibration.ac_coupling_warnings(0.0).empty());  // frequency not known
}

}  // namespace
}  // namespace oscilab::daq
