#include "daq/live/alarm_monitor.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace oscilab::daq {
namespace {

constexpr double kAlarmRateHz = 100.0;

TEST(AlarmMonitor, OneAlarmPerExcursionReArmedAfterASecondBelowNinetyPercent) {
  AlarmLimits limits;
  limits.max_abs_force_n = 2.0;
  AlarmMonitor monitor(limits, kAlarmRateHz);
  EXPECT_TRUE(monitor.watches(AlarmQuantity::Force));
  EXPECT_FALSE(monitor.watches(AlarmQuantity::RelativeDisplacement));
  std::vector<AlarmMonitor::Alarm> raised;
  // A force swinging ±3 N at 5 Hz for 2 s: one excursion, one alarm (it never stays below
  // 1.8 N for a second).
  std::uint64_t s = 0;
  for (; s < 200; ++s) {
    const double t = static_cast<double>(s) / kAlarmRateHz;
    monitor.check(AlarmQuantity::Force, s, 3.0 * std::sin(2 * 3.14159265358979 * 5 * t), raised);
  }
  ASSERT_EQ(raised.size(), 1u);
  EXPECT_EQ(raised[0].sample, 3u);  // the first sample above 2 N: sin 2π·5t > 2/3 from 0.023 s
  EXPECT_NE(raised[0].text.find("|f| = "), std::string::npos) << raised[0].text;
  EXPECT_NE(raised[0].text.find("exceeds 2"), std::string::npos) << raised[0].text;
  // 99 samples below 1.8 N do not re-arm; a value of 1.9 N restarts the count.
  monitor.check(AlarmQuantity::Force, s++, 1.9, raised);
  for (int k = 0; k < 99; ++k) monitor.check(AlarmQuantity::Force, s++, 1.0, raised);
  monitor.check(AlarmQuantity::Force, s++, 1.9, raised);
  for (int k = 0; k < 99; ++k) monitor.check(AlarmQuantity::Force, s++, 1.0, raised);
  monitor.check(AlarmQuantity::Force, s++, 2.5, raised);
  EXPECT_EQ(raised.size(), 1u);
  // A full second (100 samples) below: armed again, the next excursion alarms.
  for (int k = 0; k < 100; ++k) monitor.check(AlarmQuantity::Force, s++, 1.0, raised);
  monitor.check(AlarmQuantity::Force, s, -2.5, raised);
  ASSERT_EQ(raised.size(), 2u);
  EXPECT_EQ(raised[1].sample, s);
}

TEST(AlarmMonitor, UnwatchedOrNonFiniteValuesNeverAlarm) {
  AlarmLimits limits;
  limits.max_abs_z_m = 0.01;
  AlarmMonitor monitor(limits, kAlarmRateHz);
  std::vector<AlarmMonitor::Alarm> raised;
  monitor.check(AlarmQuantity::Force, 0, 1e9, raised);
  monitor.check(AlarmQuantity::BaseDisplacement, 0, 1e9, raised);
  monitor.check(AlarmQuantity::RelativeDisplacement, 0, std::nan(""), raised);
  EXPECT_TRUE(raised.empty());
  monitor.check(AlarmQuantity::RelativeDisplacement, 1, -0.02, raised);
  ASSERT_EQ(raised.size(), 1u);
  EXPECT_NE(raised[0].text.find("|z|"), std::string::npos);
}

}  // namespace
}  // namespace oscilab::daq
