// The event log's rows.
#include "ui/live/live_event_row.h"

#include <limits>

#include <gtest/gtest.h>

namespace oscilab::ui {
namespace {

TEST(EventRow, FormatsTimeAndMarksFaults) {
  const EventRow gap = event_row({12.5, daq::EventKind::Gap, "32 sample(s) never arrived"});
  EXPECT_EQ(gap.time, "12.500 s");
  EXPECT_EQ(gap.severity, Severity::Fault);
  const EventRow connected =
      event_row({std::numeric_limits<double>::quiet_NaN(), daq::EventKind::Connected, "sender x"});
  EXPECT_EQ(connected.time, "\u2014");
  EXPECT_EQ(connected.severity, Severity::Normal);
  EXPECT_EQ(event_row({1.0, daq::EventKind::Duplicate, "block 9"}).severity, Severity::Warning);
  EXPECT_EQ(gap.kind, "gap");
  EXPECT_EQ(event_row({1.0, daq::EventKind::Level, "", {{"f0_n", 1.0}}}).text, "{\"f0_n\":1.0}");
}

// A kind a network sender named that this program does not know is shown by the sender's name.
TEST(EventRow, ShowsAnUnknownKindByTheSendersName) {
  daq::StreamEvent event(2.0, daq::EventKind::Other, "custom");
  event.other_kind = "tare";
  EXPECT_EQ(event_row(event).kind, "tare");
  EXPECT_EQ(event_row(event).severity, Severity::Normal);
}

}  // namespace
}  // namespace oscilab::ui
