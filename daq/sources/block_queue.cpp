#include "daq/sources/block_queue.h"

#include <string>

#include "analysis/common/input_error.h"

namespace oscilab::daq {

BlockQueue::BlockQueue(std::size_t capacity, int max_rows, int max_channels)
    : max_rows_(max_rows), max_channels_(max_channels) {
  if (capacity == 0 || max_rows <= 0 || max_channels <= 0) {
    throw InputError("block queue: capacity " + std::to_string(capacity) + ", rows " +
                     std::to_string(max_rows) + " and channels " + std::to_string(max_channels) +
                     " must be positive");
  }
  slots_.resize(capacity + 1);
  for (RawBlock& slot : slots_) {
    slot.values.resize(static_cast<std::size_t>(max_rows) * static_cast<std::size_t>(max_channels));
  }
}

RawBlock* BlockQueue::begin_push() {
  const std::size_t tail = tail_.load(std::memory_order_relaxed);
  const std::size_t next = (tail + 1) % slots_.size();
  if (next == head_.load(std::memory_order_acquire)) return nullptr;  // full
  return &slots_[tail];
}

void BlockQueue::end_push() {
  const std::size_t tail = tail_.load(std::memory_order_relaxed);
  tail_.store((tail + 1) % slots_.size(), std::memory_order_release);
}

RawBlock* BlockQueue::front() {
  const std::size_t head = head_.load(std::memory_order_relaxed);
  if (head == tail_.load(std::memory_order_acquire)) return nullptr;  // empty
  return &slots_[head];
}

void BlockQueue::pop() {
  const std::size_t head = head_.load(std::memory_order_relaxed);
  head_.store((head + 1) % slots_.size(), std::memory_order_release);
}

std::size_t BlockQueue::size() const {
  const std::size_t head = head_.load(std::memory_order_acquire);
  const std::size_t tail = tail_.load(std::memory_order_acquire);
  return (tail + slots_.size() - head) % slots_.size();
}

}  // namespace oscilab::daq
