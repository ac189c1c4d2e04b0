// The event log's rows.
#include "ui/live_event_row.h"

#include <limits>

#include <gtest/gtest.h>

namespace oscilab::ui {
namespace {

TEST(EventRow, FormatsTimeAndMarksFaults) {
  const EventRow gap = event_row({12.5, "gap", "32 sample(s) never arrived"});
  EXPECT_EQ(gap.time, "12.500 s");
  EXPECT_EQ(gap.severity, Severity::Fault);
  const EventRow connected =
      event_row({std::numeric_limits<double>::quiet_NaN(), "connected", "sender x"});
  EXPECT_EQ(connected.time, "\u2014");
  EXPECT_EQ(connected.severity, Severity::Normal);
  EXPECT_EQ(event_row({1.0, "duplicate", "block 9"}).severity, Severity::Warning);
  EXPECT_EQ(event_row({1.0, "level", "", {{"f0_n", 1.0}}}).text, "{\"f0_n\":1.0}");
}

}  // namespace
}  // namespace oscilab::ui
