#pragma once

#include <atomic>
#include <cstddef>
#include <vector>

#include "daq/sources/raw_block.h"

namespace oscilab::daq {

/// Lock-free single-producer, single-consumer ring of preallocated RawBlocks between a source's
/// thread and the acquisition thread. The producer fills a slot in place (begin_push/end_push),
/// the consumer reads it in place (front/pop): no copies beyond the one into the slot, no
/// allocation after construction, no lock (acquire/release on two indices; Lamport 1977,
/// "Proving the correctness of multiprocess programs").
///
/// Thread-safety: exactly one producer thread calls begin_push/end_push and one consumer thread
/// front/pop; size() may be read from anywhere (a snapshot).
class BlockQueue {
 public:
  /// `capacity` slots, each holding up to max_rows × max_channels values. Throws InputError on
  /// non-positive sizes.
  BlockQueue(std::size_t capacity, int max_rows, int max_channels);

  /// Producer: a free slot to fill, or null when the queue is full (the consumer is behind).
  RawBlock* begin_push();
  /// Producer: publishes the slot returned by begin_push.
  void end_push();

  /// Consumer: the oldest published block, or null when empty.
  RawBlock* front();
  /// Consumer: releases the block returned by front.
  void pop();

  std::size_t size() const;
  std::size_t capacity() const { return slots_.size() - 1; }
  int max_rows() const { return max_rows_; }
  int max_channels() const { return max_channels_; }

 private:
  std::vector<RawBlock> slots_;  // one more than the capacity: full and empty differ
  int max_rows_, max_channels_;
  alignas(64) std::atomic<std::size_t> head_{0};  // next slot to read (consumer)
  alignas(64) std::atomic<std::size_t> tail_{0};  // next slot to write (producer)
};

}  // namespace oscilab::daq
