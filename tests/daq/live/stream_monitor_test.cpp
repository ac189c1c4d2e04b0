#include "daq/live/stream_monitor.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace oscilab::daq {
namespace {

struct Log {
  std::vector<std::pair<std::uint64_t, std::uint64_t>> blocks;  // (sequence, placed at)
  std::vector<std::pair<std::uint64_t, std::uint64_t>> gaps;    // (first, samples)
  std::vector<std::string> anomalies;
};

StreamMonitor monitor(Log& log, int window = 3) {
  return StreamMonitor(
      window, 4, 1,
      {[&](const RawBlock& b, std::uint64_t at) { log.blocks.emplace_back(b.sequence, at); },
       [&](std::uint64_t first, std::uint64_t n) { log.gaps.emplace_back(first, n); },
       [&](EventKind kind, std::uint64_t, std::uint64_t) {
         log.anomalies.emplace_back(to_string(kind));
       }});
}

RawBlock block(std::uint64_t sequence, std::uint64_t first_sample = ~0ull) {
  RawBlock b;
  b.sequence = sequence;
  b.first_sample = first_sample == ~0ull ? 4 * sequence : first_sample;
  b.rows = 4;
  b.channels = 1;
  b.values.assign(4, 0.0);
  return b;
}

TEST(StreamMonitor, PutsReorderedBlocksBackInPlace) {
  Log log;
  StreamMonitor m = monitor(log);
  for (std::uint64_t s : {0, 2, 1, 3}) m.push(block(s));
  ASSERT_EQ(log.blocks.size(), 4u);
  for (std::uint64_t s = 0; s < 4; ++s) EXPECT_EQ(log.blocks[s].first, s);
  EXPECT_TRUE(log.gaps.empty());
  EXPECT_EQ(m.counters().reordered, 1u);
}

TEST(StreamMonitor, DeclaresAGapWhenTheWindowFillsAndDropsTheLateBlock) {
  Log log;
  StreamMonitor m = monitor(log, 3);
  for (std::uint64_t s : {0, 2, 3, 4}) m.push(block(s));  // 1 never comes within 3 blocks
  ASSERT_EQ(log.gaps.size(), 1u);
  EXPECT_EQ(log.gaps[0], std::make_pair(std::uint64_t{4}, std::uint64_t{4}));  // samples 4..7
  ASSERT_EQ(log.blocks.size(), 4u);
  m.push(block(1));  // too late now
  EXPECT_EQ(log.anomalies, std::vector<std::string>{"late"});
  EXPECT_EQ(m.counters().lost_blocks, 1u);
  EXPECT_EQ(m.counters().gap_samples, 4u);
}

TEST(StreamMonitor, DropsDuplicatesDeliveredOrHeld) {
  Log log;
  StreamMonitor m = monitor(log);
  for (std::uint64_t s : {0, 1, 1, 3, 3, 2}) m.push(block(s));
  EXPECT_EQ(log.blocks.size(), 4u);
  EXPECT_EQ(m.counters().duplicates, 2u);
}

TEST(StreamMonitor, SeesAJumpOfTheSampleClockAsAGapAndABackwardOneAsADiscontinuity) {
  Log log;
  StreamMonitor m = monitor(log);
  m.push(block(0, 0));
  m.push(block(1, 10));  // 6 samples missing although no block is
  m.push(block(2, 12));  // overlaps: re-timed to follow on at 14
  ASSERT_EQ(log.gaps.size(), 1u);
  EXPECT_EQ(log.gaps[0], std::make_pair(std::uint64_t{4}, std::uint64_t{6}));
  EXPECT_EQ(log.anomalies, std::vector<std::string>{"discontinuity"});
  EXPECT_EQ(log.blocks[2].second, 14u);
}

TEST(StreamMonitor, FlushDeliversWhatIsHeldAfterTheLastGap) {
  Log log;
  StreamMonitor m = monitor(log, 8);
  for (std::uint64_t s : {0, 3, 4}) m.push(block(s));
  EXPECT_EQ(log.blocks.size(), 1u);
  m.flush();
  EXPECT_EQ(log.blocks.size(), 3u);
  EXPECT_EQ(log.gaps[0], std::make_pair(std::uint64_t{4}, std::uint64_t{8}));
}

// A sequence far ahead (a peer's 2^63) costs what a near one costs: the missing blocks are
// counted at once, not walked one by one, and a block from before the jump is still told late.
TEST(StreamMonitor, ASequenceFarAheadIsCountedAtOnceWithoutWalkingTheGap) {
  Log log;
  StreamMonitor m = monitor(log, 2);
  constexpr std::uint64_t kFar = std::uint64_t{1} << 63;
  m.push(block(0, 0));
  m.push(block(kFar, 4));
  m.push(block(kFar + 1, 8));  // the window is full: what lies before kFar is declared lost
  ASSERT_EQ(log.blocks.size(), 3u);
  EXPECT_EQ(m.counters().lost_blocks, kFar - 1);
  EXPECT_TRUE(log.gaps.empty()) << "the sample clock did not jump";
  m.push(block(kFar - 1, 12));  // among the newest lost sequences remembered
  m.push(block(1, 12));         // too old to be remembered: a duplicate, still dropped
  EXPECT_EQ(log.anomalies, (std::vector<std::string>{"late", "duplicate"}));
  EXPECT_EQ(log.blocks.size(), 3u);
}

}  // namespace
}  // namespace oscilab::daq
