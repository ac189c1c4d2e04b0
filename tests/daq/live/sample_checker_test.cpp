#include "daq/live/sample_checker.h"

#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

namespace oscilab::daq {
namespace {

constexpr double kNotANumber = std::numeric_limits<double>::quiet_NaN();

RawBlock block(std::uint64_t first, const std::vector<std::pair<double, double>>& rows) {
  RawBlock b;
  b.first_sample = first;
  b.rows = static_cast<int>(rows.size());
  b.channels = 2;
  for (const auto& [a, c] : rows) b.values.insert(b.values.end(), {a, c});
  return b;
}

SampleChecker checker() {
  // Channel "b": stored counts, physical = 0.5 × stored + 1 within (−9, 9); "y": no range.
  return SampleChecker({{"b", 0.5, 1.0, std::pair{-9.0, 9.0}}, {"y", 1.0, 0.0, std::nullopt}}, 8);
}

TEST(SampleChecker, ARunOfBadSamplesAcrossBlocksIsOneRunReportedWhenItEnds) {
  SampleChecker c = checker();
  std::vector<SampleChecker::Run> closed;
  // Stored 16 → physical 9: at the range's edge, saturated; 15.9 → 8.95 is not.
  auto counts = c.check(block(0, {{0, 0}, {16, 0}, {16, kNotANumber}, {15.9, 0}}), 0, closed);
  EXPECT_EQ(counts.saturated, 2u);
  EXPECT_EQ(counts.non_finite, 1u);
  ASSERT_EQ(closed.size(), 2u);  // both ended at row 3, reported in channel order
  EXPECT_EQ(closed[0].kind, BadSampleKind::Saturated);
  EXPECT_EQ(closed[0].channel, 0);
  EXPECT_EQ(closed[0].from, 1u);
  EXPECT_EQ(closed[0].to, 2u);
  EXPECT_EQ(closed[0].count, 2u);
  EXPECT_EQ(closed[1].kind, BadSampleKind::NonFinite);
  EXPECT_EQ(closed[1].channel, 1);
  EXPECT_EQ(closed[1].from, 2u);
  EXPECT_EQ(closed[1].to, 2u);
  EXPECT_EQ(closed[1].count, 1u);
  EXPECT_FALSE(c.bad_row(0));
  EXPECT_TRUE(c.bad_row(1));
  EXPECT_TRUE(c.bad_row(2));
  EXPECT_FALSE(c.bad_row(3));

  closed.clear();
  counts = c.check(block(4, {{0, 0}, {-20, kNotANumber}}), 4, closed);  // −9: the low edge
  EXPECT_TRUE(closed.empty());                                          // both runs still open
  counts = c.check(block(6, {{-20, kNotANumber}, {-20, kNotANumber}}), 6, closed);
  EXPECT_TRUE(closed.empty());
  c.finish(closed);  // the stream ended inside the runs
  ASSERT_EQ(closed.size(), 2u);
  for (const SampleChecker::Run& run : closed) {
    EXPECT_EQ(run.from, 5u);
    EXPECT_EQ(run.to, 7u);
    EXPECT_EQ(run.count, 3u);
  }
  EXPECT_STREQ(to_string(BadSampleKind::NonFinite), "non-finite");
  EXPECT_STREQ(to_string(BadSampleKind::Saturated), "saturated");
}

TEST(SampleChecker, InfinitiesAreNotSaturationAndCleanBlocksCloseNothing) {
  SampleChecker c = checker();
  std::vector<SampleChecker::Run> closed;
  const double inf = std::numeric_limits<double>::infinity();
  const auto counts = c.check(block(0, {{inf, 1}, {1, 1}}), 0, closed);
  EXPECT_EQ(counts.non_finite, 1u);
  EXPECT_EQ(counts.saturated, 0u);  // not finite: counted once, as non-finite
  ASSERT_EQ(closed.size(), 1u);
  closed.clear();
  c.check(block(2, {{1, 1}, {2, 2}}), 2, closed);
  EXPECT_TRUE(closed.empty());
}

}  // namespace
}  // namespace oscilab::daq
