#include "daq/jack/frame_slot_ring.h"

namespace oscilab::daq {

void FrameSlotRing::allocate(std::size_t slots, std::size_t frames, std::size_t channels) {
  slots_.assign(slots + 1, FrameSlot{});
  for (FrameSlot& slot : slots_) slot.data.assign(frames * channels, 0.0f);
  frames_ = frames;
  head_.store(0);
  tail_.store(0);
}

FrameSlot* FrameSlotRing::begin_push() {
  const std::size_t tail = tail_.load(std::memory_order_relaxed);
  if ((tail + 1) % slots_.size() == head_.load(std::memory_order_acquire)) return nullptr;
  return &slots_[tail];
}

void FrameSlotRing::end_push() {
  const std::size_t tail = tail_.load(std::memory_order_relaxed);
  tail_.store((tail + 1) % slots_.size(), std::memory_order_release);
}

FrameSlot* FrameSlotRing::front() {
  const std::size_t head = head_.load(std::memory_order_relaxed);
  if (head == tail_.load(std::memory_order_acquire)) return nullptr;
  return &slots_[head];
}

void FrameSlotRing::pop() {
  const std::size_t head = head_.load(std::memory_order_relaxed);
  head_.store((head + 1) % slots_.size(), std::memory_order_release);
}

}  // namespace oscilab::daq
