// Fault counting from logged events and colouring by how fresh a fault is.
#include "ui/live/live_faults.h"

#include <string>

#include <gtest/gtest.h>

namespace oscilab::ui {
namespace {

daq::StreamEvent event(const std::string& kind, nlohmann::json data = nlohmann::json::object()) {
  return {1.0, daq::event_kind_from_string(kind), "", std::move(data)};
}

TEST(FaultCounts, CountsLoggedFaultsAndTakesTheLargerOfTheAcquisitionsCounts) {
  FaultCounts counts;
  counts.add(event("gap", {{"samples", 32}}));
  counts.add(event("gap", {{"samples", 64}}));
  counts.add(event("duplicate", {{"sequence", 90}}));
  counts.add(event("reordered"));
  counts.add(event("non-finite", {{"samples", 3}}));
  counts.add(event("saturated", {{"samples", 1}}));
  counts.add(event("overflow", {{"blocks", 100}}));
  counts.add(event("alarm"));
  counts.add(event("mark"));
  counts.add(event("level", {{"f0_n", 1.0}}));
  EXPECT_EQ(counts.gaps, 2u);
  EXPECT_EQ(counts.gap_samples, 96u);
  EXPECT_EQ(counts.duplicates, 1u);
  EXPECT_EQ(counts.reordered, 1u);
  EXPECT_EQ(counts.non_finite_samples, 3u);
  EXPECT_EQ(counts.saturated_samples, 1u);
  EXPECT_EQ(counts.overflowed_blocks, 100u);
  EXPECT_EQ(counts.alarms, 1u);

  daq::AcquisitionStatus status;  // after stop: the StreamMonitor's exact counts
  status.gaps = 2;
  status.gap_samples = 96;
  status.overflowed_blocks = 137;  // the source's counter: events come once per 100
  status.non_finite_samples = 3;
  const FaultCounts merged = counts.merged(status);
  EXPECT_EQ(merged.gap_samples, 96u);
  EXPECT_EQ(merged.overflowed_blocks, 137u);
  EXPECT_EQ(merged.duplicates, 1u);
}

TEST(FaultTracker, ACounterThatRoseIsRedThenAmber) {
  FaultTracker tracker(5.0);
  FaultCounts counts;
  tracker.update(counts, 0.0);
  EXPECT_EQ(tracker.severity("gaps", 0.0), Severity::Normal);
  counts.gaps = 1;
  counts.gap_samples = 32;
  tracker.update(counts, 10.0);
  EXPECT_EQ(tracker.severity("gaps", 10.0), Severity::Fault);
  EXPECT_EQ(tracker.severity("gaps", 14.9), Severity::Fault);
  tracker.update(counts, 15.1);  // no new gap
  EXPECT_EQ(tracker.severity("gaps", 15.1), Severity::Warning);
  EXPECT_EQ(tracker.severity("duplicates", 15.1), Severity::Normal);
}

}  // namespace
}  // namespace oscilab::ui
