#include "daq/sources/withheld_samples.h"

#include <gtest/gtest.h>

namespace oscilab::daq {
namespace {

TEST(WithheldSamples, WithholdsHalfOpenIntervals) {
  WithheldSamples withheld;
  withheld.add(10, 20);
  withheld.add(30, 30);  // empty: nothing
  EXPECT_FALSE(withheld.contains(9));
  EXPECT_TRUE(withheld.contains(10));
  EXPECT_TRUE(withheld.contains(19));
  EXPECT_FALSE(withheld.contains(20));
  EXPECT_FALSE(withheld.contains(30));
  EXPECT_EQ(withheld.intervals().size(), 1u);
}

TEST(WithheldSamples, MergesOverlappingAndTouchingIntervals) {
  WithheldSamples withheld;
  withheld.add(10, 20);
  withheld.add(15, 25);  // overlaps
  withheld.add(25, 30);  // touches
  withheld.add(5, 10);   // touches from below
  ASSERT_EQ(withheld.intervals().size(), 1u);
  EXPECT_EQ(withheld.intervals()[0].first, 5u);
  EXPECT_EQ(withheld.intervals()[0].second, 30u);
}

TEST(WithheldSamples, BeyondItsBoundTheLastIntervalGrowsToCoverMore) {
  WithheldSamples withheld;
  for (std::uint64_t i = 0; i < WithheldSamples::kMaxIntervals; ++i)
    withheld.add(10 * i, 10 * i + 1);
  const std::size_t capacity = withheld.intervals().capacity();
  withheld.add(100000, 100005);
  EXPECT_EQ(withheld.intervals().size(), WithheldSamples::kMaxIntervals);
  EXPECT_EQ(withheld.intervals().capacity(), capacity);  // no allocation
  // More is withheld, never less: the new interval and what lies between.
  EXPECT_TRUE(withheld.contains(100004));
  EXPECT_TRUE(withheld.contains(50000));
}

TEST(WithheldSamples, ForgetsTheIntervalsWhollyBehindTheOutput) {
  WithheldSamples withheld;
  withheld.add(10, 20);
  withheld.add(30, 40);
  withheld.drop_before(20);
  ASSERT_EQ(withheld.intervals().size(), 1u);
  EXPECT_EQ(withheld.intervals()[0].first, 30u);
  withheld.drop_before(35);  // partly behind: kept
  EXPECT_TRUE(withheld.contains(36));
}

}  // namespace
}  // namespace oscilab::daq
