#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace oscilab::daq {

/// One period of a sound card's frames (or part of one) as JACK's process callback saw it.
struct FrameSlot {
  std::uint32_t frame_time = 0;  // the server's frame clock at the slot's first frame
  std::uint32_t frames = 0;
  std::uint32_t disconnected = 0;  // bit c: channel c's port had no connection
  std::vector<float> data;         // frames × channels, interleaved; capacity fixed
};

/// Lock-free single-producer, single-consumer ring of preallocated FrameSlots between JACK's
/// real-time process callback and the JACK source's thread (as BlockQueue between a source and
/// the acquisition): the producer fills a slot in place, the consumer reads it in place; no
/// allocation after allocate(), no lock.
///
/// Thread-safety: allocate() while neither side runs; then one producer thread calls
/// begin_push/end_push and one consumer thread front/pop.
class FrameSlotRing {
 public:
  /// `slots` slots of `frames` × `channels` samples each (every slot's content zeroed).
  void allocate(std::size_t slots, std::size_t frames, std::size_t channels);
  std::size_t slot_frames() const { return frames_; }
  std::size_t capacity() const { return slots_.empty() ? 0 : slots_.size() - 1; }

  /// Producer: a free slot to fill, or null when the ring is full (the consumer is behind).
  FrameSlot* begin_push();
  /// Producer: publishes the slot returned by begin_push.
  void end_push();
  /// Consumer: the oldest published slot, or null when empty.
  FrameSlot* front();
  /// Consumer: releases the slot returned by front.
  void pop();

 private:
  std::vector<FrameSlot> slots_;  // one more than the capacity: full and empty differ
  std::size_t frames_ = 0;
  alignas(64) std::atomic<std::size_t> head_{0};  // next slot to read (consumer)
  alignas(64) std::atomic<std::size_t> tail_{0};  // next slot to write (producer)
};

}  // namespace oscilab::daq
