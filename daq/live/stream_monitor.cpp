#include "daq/live/stream_monitor.h"

#include <algorithm>

#include "analysis/common/input_error.h"

namespace oscilab::daq {
namespace {

constexpr std::size_t kLostMemory = 1024;  // sequences remembered as lost (late vs duplicate)

void copy_block(const RawBlock& from, RawBlock& to) {
  to.sequence = from.sequence;
  to.first_sample = from.first_sample;
  to.rows = from.rows;
  to.channels = from.channels;
  to.delivered = from.delivered;
  std::copy_n(from.values.begin(), static_cast<std::ptrdiff_t>(from.rows) * from.channels,
              to.values.begin());
}

}  // namespace

StreamMonitor::StreamMonitor(int reorder_window, int max_rows, int channels, Output output)
    : output_(std::move(output)) {
  if (reorder_window < 1 || max_rows < 1 || channels < 1) {
    throw InputError("stream monitor: window, rows and channels must be positive");
  }
  held_.resize(static_cast<std::size_t>(reorder_window));
  used_.assign(held_.size(), false);
  for (RawBlock& slot : held_) {
    slot.values.resize(static_cast<std::size_t>(max_rows) * static_cast<std::size_t>(channels));
  }
  lost_.reserve(kLostMemory);
}

void StreamMonitor::deliver(const RawBlock& block) {
  if (block.first_sample > next_sample_) {
    ++counters_.gaps;
    counters_.gap_samples += block.first_sample - next_sample_;
    output_.gap(next_sample_, block.first_sample - next_sample_);
    next_sample_ = block.first_sample;
  }
  if (block.first_sample < next_sample_) {
    // The sender's clock went back: keep the samples, re-timed to follow on.
    ++counters_.discontinuities;
    output_.anomaly(EventKind::Discontinuity, block.sequence, next_sample_);
  }
  output_.block(block, next_sample_);
  ++counters_.blocks;
  next_sequence_ = block.sequence + 1;
  next_sample_ += static_cast<std::uint64_t>(block.rows);
}

void StreamMonitor::release_held() {
  bool progress = true;
  while (progress && held_count_ > 0) {
    progress = false;
    for (std::size_t i = 0; i < held_.size(); ++i) {
      if (used_[i] && held_[i].sequence == next_sequence_) {
        deliver(held_[i]);
        used_[i] = false;
        --held_count_;
        progress = true;
      }
    }
  }
}

void StreamMonitor::give_up_missing() {
  // The oldest held block: everything before it is lost.
  std::size_t oldest = held_.size();
  for (std::size_t i = 0; i < held_.size(); ++i) {
    if (used_[i] && (oldest == held_.size() || held_[i].sequence < held_[oldest].sequence)) {
      oldest = i;
    }
  }
  if (oldest == held_.size()) return;
  // Counted at once and only the newest kLostMemory remembered: a sequence far ahead (a peer's
  // 2^63) costs no more than a near one.
  const std::uint64_t missing = held_[oldest].sequence - next_sequence_;
  counters_.lost_blocks += missing;
  const std::uint64_t remembered = std::min<std::uint64_t>(missing, kLostMemory);
  const std::size_t keep = std::min(lost_.size(), kLostMemory - remembered);
  lost_.erase(lost_.begin(), lost_.end() - static_cast<std::ptrdiff_t>(keep));
  for (std::uint64_t s = held_[oldest].sequence - remembered; s < held_[oldest].sequence; ++s) {
    lost_.push_back(s);
  }
  next_sequence_ = held_[oldest].sequence;
  release_held();
}

void StreamMonitor::push(const RawBlock& block) {
  if (!started_) {
    started_ = true;
    next_sequence_ = block.sequence;
    next_sample_ = block.first_sample;
  }
  if (block.sequence == next_sequence_) {
    const bool was_holding = held_count_ > 0;
    deliver(block);
    if (was_holding) {
      ++counters_.reordered;
      release_held();
    }
    return;
  }
  if (block.sequence < next_sequence_) {
    const bool late = std::find(lost_.begin(), lost_.end(), block.sequence) != lost_.end();
    ++(late ? counters_.late : counters_.duplicates);
    output_.anomaly(late ? EventKind::Late : EventKind::Duplicate, block.sequence,
                    block.first_sample);
    return;
  }
  // Ahead: hold it (a duplicate of a held block is dropped).
  for (std::size_t i = 0; i < held_.size(); ++i) {
    if (used_[i] && held_[i].sequence == block.sequence) {
      ++counters_.duplicates;
      output_.anomaly(EventKind::Duplicate, block.sequence, block.first_sample);
      return;
    }
  }
  if (held_count_ == static_cast<int>(held_.size())) give_up_missing();
  if (block.sequence == next_sequence_) {  // the give-up made it the next one
    deliver(block);
    release_held();
    return;
  }
  for (std::size_t i = 0; i < held_.size(); ++i) {
    if (!used_[i]) {
      copy_block(block, held_[i]);
      used_[i] = true;
      ++held_count_;
      break;
    }
  }
  if (held_count_ == static_cast<int>(held_.size())) give_up_missing();
}

void StreamMonitor::flush() {
  while (held_count_ > 0) give_up_missing();
}

}  // namespace oscilab::daq
