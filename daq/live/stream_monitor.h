#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "daq/sources/raw_block.h"
#include "daq/sources/stream_event.h"

namespace oscilab::daq {

/// Puts a source's blocks back into one continuous, ordered stream and says what was wrong with
/// it: the first line of fault handling, before any sample is trusted.
///
/// - In order (sequence == next): delivered.
/// - Ahead of the next (a block is missing): held, up to `reorder_window` blocks; when the
///   missing block arrives in time, the held ones follow it (counted as reordered); when the
///   window fills, the missing blocks are declared lost and a gap of the samples between is
///   delivered (the consumer records it as NaN and excludes the cycles it touches).
/// - Behind the next: a duplicate (delivered before) or late (declared lost already): dropped.
/// - A block whose sample clock jumps forward although no sequence is missing: a gap of the
///   missing samples; backwards (overlap): a discontinuity, the block is re-timed to follow on.
///
/// Storage for held blocks is sized at construction: nothing is allocated per block.
/// Not thread-safe: the acquisition thread owns it.
class StreamMonitor {
 public:
  struct Counters {
    std::uint64_t blocks = 0;
    std::uint64_t gaps = 0;  // gap events (each one run of missing samples)
    std::uint64_t gap_samples = 0;
    std::uint64_t lost_blocks = 0;
    std::uint64_t duplicates = 0;
    std::uint64_t late = 0;
    std::uint64_t reordered = 0;
    std::uint64_t discontinuities = 0;
  };
  /// What the monitor hands on, in stream order.
  struct Output {
    /// A block to use, placed at `first_sample` on the stream clock (its own first_sample,
    /// except after the clock went back).
    std::function<void(const RawBlock& block, std::uint64_t first_sample)> block;
    /// `samples` samples from first_sample on never arrived.
    std::function<void(std::uint64_t first_sample, std::uint64_t samples)> gap;
    /// Blocks dropped (Duplicate or Late) or re-timed (Discontinuity).
    std::function<void(EventKind kind, std::uint64_t sequence, std::uint64_t first_sample)> anomaly;
  };

  StreamMonitor(int reorder_window, int max_rows, int channels, Output output);

  void push(const RawBlock& block);
  /// The source ended: declare what is still missing lost and deliver what is held.
  void flush();

  const Counters& counters() const { return counters_; }
  std::uint64_t next_sample() const { return next_sample_; }

 private:
  void deliver(const RawBlock& block);
  void release_held();
  void give_up_missing();

  Output output_;
  std::vector<RawBlock> held_;  // slots; used_[i] tells which hold a block
  std::vector<bool> used_;
  int held_count_ = 0;
  bool started_ = false;
  std::uint64_t next_sequence_ = 0, next_sample_ = 0;
  std::uint64_t lost_below_ = 0;     // sequences below this that were never delivered are "late"
  std::vector<std::uint64_t> lost_;  // recently declared lost (bounded), to tell late from dup
  Counters counters_;
};

}  // namespace oscilab::daq
