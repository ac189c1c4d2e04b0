#include "ui/display_units.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace oscilab::ui {
namespace {

TEST(DisplayUnit, DisplacementTakesTheLargestPrefixThatReadsAtLeastOne) {
  EXPECT_EQ(choose_display_unit("m", 1.5).symbol, "m");
  EXPECT_EQ(choose_display_unit("m", 0.004).symbol, "mm");
  EXPECT_EQ(choose_display_unit("m", 0.999).symbol, "mm");
  EXPECT_EQ(choose_display_unit("m", 2e-5).symbol, "µm");
  EXPECT_EQ(choose_display_unit("m", 3e-9).symbol, "nm");
  EXPECT_EQ(choose_display_unit("m", 1e-12).symbol, "nm");  // the smallest known prefix
  EXPECT_DOUBLE_EQ(choose_display_unit("m", 0.004).si_per_unit, 1e-3);
  EXPECT_DOUBLE_EQ(choose_display_unit("m", 2e-5).si_per_unit, 1e-6);
}

TEST(DisplayUnit, AccelerationStaysInMetresPerSecondSquaredDownToATenth) {
  EXPECT_EQ(choose_display_unit("m/s^2", 25.0).symbol, "m/s²");
  EXPECT_EQ(choose_display_unit("m/s^2", 0.3).symbol, "m/s²");
  EXPECT_EQ(choose_display_unit("m/s^2", 0.05).symbol, "mm/s²");
  EXPECT_DOUBLE_EQ(choose_display_unit("m/s^2", 0.05).si_per_unit, 1e-3);
}

TEST(DisplayUnit, VelocityAndForceUsePrefixes) {
  EXPECT_EQ(choose_display_unit("m/s", 0.2).symbol, "mm/s");
  EXPECT_EQ(choose_display_unit("m/s", 3e-4).symbol, "µm/s");
  EXPECT_EQ(choose_display_unit("N", 0.35).symbol, "mN");
  EXPECT_EQ(choose_display_unit("N", 12.0).symbol, "N");
  EXPECT_EQ(choose_display_unit("N", 2500.0).symbol, "kN");
}

TEST(DisplayUnit, ZeroOrNonFiniteRangeKeepsTheUnprefixedUnit) {
  EXPECT_EQ(choose_display_unit("m", 0.0).symbol, "m");
  EXPECT_EQ(choose_display_unit("N", 0.0).symbol, "N");
  EXPECT_EQ(choose_display_unit("m/s^2", std::numeric_limits<double>::infinity()).symbol, "m/s²");
  EXPECT_EQ(choose_display_unit("m", std::nan("")).symbol, "m");
}

TEST(DisplayUnit, UnknownUnitIsShownAsItIs) {
  const DisplayUnit volt = choose_display_unit("V", 1e-3);
  EXPECT_EQ(volt.symbol, "V");
  EXPECT_DOUBLE_EQ(volt.si_per_unit, 1.0);
  EXPECT_EQ(choose_display_unit("rad/s^2", 1.0).symbol, "rad/s²");
}

TEST(DisplayUnit, DecimalsGiveTheLargestValueFourSignificantDigits) {
  EXPECT_EQ(choose_display_unit("m", 0.004).decimals, 3);       // 4.000 mm
  EXPECT_EQ(choose_display_unit("m", 0.0125).decimals, 2);      // 12.50 mm
  EXPECT_EQ(choose_display_unit("N", 0.25).decimals, 1);        // 250.0 mN
  EXPECT_EQ(choose_display_unit("m/s^2", 0.5).decimals, 4);     // 0.5000 m/s²
  EXPECT_EQ(choose_display_unit("m/s^2", 2500.0).decimals, 0);  // 2500 m/s²
}

TEST(DisplayUnit, ConvertsAndFormatsWithTheUnitsDecimals) {
  const DisplayUnit mm = choose_display_unit("m", 0.004);
  EXPECT_DOUBLE_EQ(mm.to_display(-0.0031416), -3.1416);
  EXPECT_EQ(format_value(-0.0031416, mm), "-3.142 mm");
  EXPECT_EQ(format_value(9.80665, choose_display_unit("m/s^2", 9.8)), "9.807 m/s²");
  EXPECT_EQ(format_value(-1e-7, mm), "0.000 mm");  // no "-0.000"
}

TEST(DisplayUnit, EachChannelOfARecordingGetsItsOwnUnit) {
  daq::Recording recording;
  recording.sidecar.sample_rate_hz = 100.0;
  recording.sidecar.channels.resize(2);
  recording.sidecar.channels[0].quantity = daq::Quantity::Acceleration;
  recording.sidecar.channels[1].quantity = daq::Quantity::Displacement;
  recording.samples_si.resize(3, 2);
  recording.samples_si << 1.0, 1e-5, -4.0, -3e-5, 2.0, 2e-5;
  const std::vector<DisplayUnit> units = choose_display_units(daq::hold_recording(recording));
  ASSERT_EQ(units.size(), 2u);
  EXPECT_EQ(units[0].symbol, "m/s²");
  EXPECT_EQ(units[1].symbol, "µm");  // largest |y| is 30 µm
}

}  // namespace
}  // namespace oscilab::ui
