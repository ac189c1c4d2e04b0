#include "ui/time_window.h"

#include <limits>

#include <gtest/gtest.h>

namespace oscilab::ui {
namespace {

constexpr TimeWindow kFull{0.0, 100.0};

TEST(TimeWindow, KeepsARequestInsideTheRecord) {
  const TimeWindow window = clamp_time_window({10.0, 20.0}, kFull, 0.1);
  EXPECT_DOUBLE_EQ(window.start_s, 10.0);
  EXPECT_DOUBLE_EQ(window.end_s, 20.0);
}

TEST(TimeWindow, ShiftsAPanPastAnEndBackKeepingItsWidth) {
  const TimeWindow left = clamp_time_window({-5.0, 5.0}, kFull, 0.1);
  EXPECT_DOUBLE_EQ(left.start_s, 0.0);
  EXPECT_DOUBLE_EQ(left.end_s, 10.0);
  const TimeWindow right = clamp_time_window({95.0, 110.0}, kFull, 0.1);
  EXPECT_DOUBLE_EQ(right.start_s, 85.0);
  EXPECT_DOUBLE_EQ(right.end_s, 100.0);
}

TEST(TimeWindow, ZoomOutStopsAtTheWholeRecord) {
  const TimeWindow window = clamp_time_window({-50.0, 180.0}, kFull, 0.1);
  EXPECT_DOUBLE_EQ(window.start_s, 0.0);
  EXPECT_DOUBLE_EQ(window.end_s, 100.0);
}

TEST(TimeWindow, ZoomInStopsAtTheMinimumWidthAboutTheCentre) {
  const TimeWindow window = clamp_time_window({50.0, 50.01}, kFull, 1.0);
  EXPECT_DOUBLE_EQ(window.start_s, 49.505);
  EXPECT_DOUBLE_EQ(window.end_s, 50.505);
}

TEST(TimeWindow, InvalidRequestGivesTheWholeRecord) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_DOUBLE_EQ(clamp_time_window({nan, 1.0}, kFull, 0.1).end_s, 100.0);
  EXPECT_DOUBLE_EQ(clamp_time_window({20.0, 10.0}, kFull, 0.1).start_s, 0.0);
}

}  // namespace
}  // namespace oscilab::ui
