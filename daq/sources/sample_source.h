#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "daq/recording/sidecar.h"
#include "daq/sources/block_queue.h"
#include "daq/sources/stream_event.h"

namespace oscilab::daq {

/// A network receiver's counters (NetSource).
struct NetworkCounters {
  std::uint64_t connections = 0;        // senders accepted
  std::uint64_t malformed_frames = 0;   // frames rejected
  std::uint64_t layout_mismatches = 0;  // senders refused for their layout
};

/// A sound card's counters (JackSource).
struct JackCounters {
  std::uint64_t xruns = 0;                // xruns the server reported
  std::uint64_t server_losses = 0;        // the server shut down (or dropped the client)
  std::uint64_t port_disconnections = 0;  // a capture port lost its connection
  std::uint64_t rate_changes = 0;         // the server's sample rate changed
  std::uint64_t dropped_frames = 0;       // frames the ring had no room for
  std::uint64_t clipped_samples = 0;      // input samples at the interface's full scale
  std::uint64_t reconnections = 0;        // the server came back and the source with it
  std::uint64_t failed_reconnects = 0;    // tries to reopen a gone server that failed
};

/// Counters of a source, read from any thread: every source's, then its kind's (zero for the
/// other kinds).
struct SourceCounters {
  std::uint64_t blocks_delivered = 0;
  std::uint64_t samples_delivered = 0;
  std::uint64_t blocks_overflowed = 0;  // dropped because the queue was full
  NetworkCounters network;
  JackCounters jack;
};

/// One live source of samples (virtual rig, file replay, network stream), running on its own
/// thread and delivering RawBlocks into a BlockQueue. The stream's meaning (channels,
/// calibration, rate, excitation) is a Sidecar, known before the first block.
///
/// Thread-safety: start/stop/layout/counters/take_events/finished from the controlling thread;
/// run() on the source's thread; the queue is the only data path between them.
class SampleSource {
 public:
  virtual ~SampleSource();
  SampleSource(const SampleSource&) = delete;
  SampleSource& operator=(const SampleSource&) = delete;

  /// What the samples mean. Rig and replay know it from the start; a network source learns it
  /// from its first sender (empty until then) unless it was given one to expect.
  std::optional<Sidecar> layout() const;
  /// Rows per block this source delivers at most (sizes the queue).
  virtual int max_block_rows() const = 0;
  /// Channels per block at most (sizes the queue): the layout's, when known from the start.
  virtual int max_channels() const;
  /// A short description for the status bar, e.g. "virtual rig" or "net 127.0.0.1:5025".
  virtual std::string describe() const = 0;

  /// Starts the source's thread delivering into `queue` (which must outlive stop()).
  void start(BlockQueue& queue);
  /// Asks the thread to end and joins it. Idempotent.
  void stop();
  /// The source ended by itself (end of file, duration reached) or failed.
  bool finished() const { return finished_.load(std::memory_order_acquire); }

  SourceCounters counters() const;
  /// Events posted since the last call, oldest first.
  std::vector<StreamEvent> take_events();

 protected:
  SampleSource() = default;
  /// The source's loop: deliver blocks until stop_requested() or the end of the source.
  virtual void run() = 0;
  /// Called by stop() before joining, to wake a blocking run() (e.g. close a socket).
  virtual void interrupt() {}
  /// Fills in the counters of the source's kind (counters() calls it from any thread).
  virtual void kind_counters(SourceCounters&) const {}

  bool stop_requested() const { return stop_.load(std::memory_order_acquire); }
  void set_layout(const Sidecar& sidecar);
  void post_event(StreamEvent event);

  /// A slot to fill, or null when the queue is full. With `wait`, waits for room (polling every
  /// millisecond) unless stop is requested: replay as fast as possible must not drop; a live
  /// source must not wait (its hardware would overrun), so it drops and counts an overflow.
  RawBlock* begin_block(bool wait);
  /// Waits up to `max_wait` for room: a network source holds back (TCP's flow control then
  /// slows the sender, losing nothing) before it drops.
  RawBlock* begin_block_within(std::chrono::milliseconds max_wait);
  /// Publishes the block filled after begin_block.
  void end_block(RawBlock& block);
  /// Counts a block the queue had no room for (and posts an overflow event once in a while).
  void count_overflow(std::uint64_t first_sample);

 private:
  void thread_main();

  BlockQueue* queue_ = nullptr;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> finished_{false};
  std::atomic<std::uint64_t> blocks_{0}, samples_{0}, overflowed_{0};
  mutable std::mutex mutex_;  // guards layout_ and events_ (rare, never per sample)
  std::optional<Sidecar> layout_;
  std::vector<StreamEvent> events_;
};

}  // namespace oscilab::daq
