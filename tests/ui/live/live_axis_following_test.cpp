// Display units and axis ranges that follow live data.
#include "ui/live/live_axis_following.h"

#include <cmath>
#include <optional>

#include <gtest/gtest.h>

namespace oscilab::ui {
namespace {

TEST(StickyDisplayUnit, KeepsTheUnitNearAPrefixBoundary) {
  const DisplayUnit mm = sticky_display_unit(std::nullopt, "m", 4e-3);
  EXPECT_EQ(mm.symbol, "mm");
  EXPECT_EQ(sticky_display_unit(mm, "m", 0.6e-3).symbol, "mm");  // 0.6 mm: still mm
  EXPECT_EQ(sticky_display_unit(mm, "m", 0.3e-3).symbol, "\u00b5m");
  EXPECT_EQ(sticky_display_unit(mm, "m", 0.0).symbol, "mm");  // no data: unchanged
  EXPECT_EQ(sticky_display_unit(mm, "m", 2.5).symbol, "m");
}

TEST(FollowRange, GrowsAtOnceAndShrinksOnlyWhenTheDataFillLittle) {
  const AxisRange first = follow_range(std::nullopt, -1.0, 1.0);
  EXPECT_DOUBLE_EQ(first.lo, -1.2);
  EXPECT_DOUBLE_EQ(first.hi, 1.2);
  const AxisRange same = follow_range(first, -0.9, 0.8);  // inside, fills 71 %: unchanged
  EXPECT_EQ(same.lo, first.lo);
  EXPECT_EQ(same.hi, first.hi);
  const AxisRange grown = follow_range(first, -1.0, 2.0);
  EXPECT_GE(grown.hi, 2.0);
  const AxisRange shrunk = follow_range(grown, -0.1, 0.1);
  EXPECT_NEAR(shrunk.hi, 0.12, 1e-12);
  EXPECT_EQ(follow_range(first, std::nan(""), 1.0).lo, first.lo);
}

}  // namespace
}  // namespace oscilab::ui
