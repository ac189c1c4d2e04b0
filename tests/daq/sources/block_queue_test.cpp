#include "daq/sources/block_queue.h"

#include <thread>

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"

namespace oscilab::daq {
namespace {

TEST(BlockQueue, HoldsCapacityBlocksThenRefuses) {
  BlockQueue queue(3, 4, 2);
  for (int i = 0; i < 3; ++i) {
    RawBlock* slot = queue.begin_push();
    ASSERT_NE(slot, nullptr);
    slot->sequence = static_cast<std::uint64_t>(i);
    queue.end_push();
  }
  EXPECT_EQ(queue.size(), 3u);
  EXPECT_EQ(queue.begin_push(), nullptr);  // full: a live source counts an overflow
  ASSERT_NE(queue.front(), nullptr);
  EXPECT_EQ(queue.front()->sequence, 0u);
  queue.pop();
  EXPECT_NE(queue.begin_push(), nullptr);
}

TEST(BlockQueue, DeliversEveryBlockInOrderAcrossThreads) {
  // 200 000 blocks through 8 slots between two threads: any lost, repeated or torn block (a
  // broken acquire/release pairing) shows as a wrong sequence or payload.
  BlockQueue queue(8, 16, 2);
  constexpr std::uint64_t kBlocks = 200000;
  std::thread producer([&] {
    for (std::uint64_t i = 0; i < kBlocks;) {
      RawBlock* slot = queue.begin_push();
      if (!slot) {
        std::this_thread::yield();
        continue;
      }
      slot->sequence = i;
      slot->rows = 16;
      slot->channels = 2;
      for (int k = 0; k < 32; ++k) slot->values[static_cast<std::size_t>(k)] = double(i) + k;
      queue.end_push();
      ++i;
    }
  });
  std::uint64_t expected = 0;
  bool payload_ok = true;
  while (expected < kBlocks) {
    RawBlock* block = queue.front();
    if (!block) {
      std::this_thread::yield();
      continue;
    }
    ASSERT_EQ(block->sequence, expected);
    for (int k = 0; k < 32; ++k) {
      payload_ok &= block->values[static_cast<std::size_t>(k)] == double(expected) + k;
    }
    queue.pop();
    ++expected;
  }
  producer.join();
  EXPECT_TRUE(payload_ok);
  EXPECT_EQ(queue.size(), 0u);
}

TEST(BlockQueue, ThrowsInputErrorOnZeroSizes) {
  EXPECT_THROW(BlockQueue(0, 4, 2), InputError);
  EXPECT_THROW(BlockQueue(4, 0, 2), InputError);
}

}  // namespace
}  // namespace oscilab::daq
