#include "daq/sources/sample_source.h"

#include <chrono>
#include <exception>
#include <limits>

namespace oscilab::daq {

SampleSource::~SampleSource() = default;

std::optional<Sidecar> SampleSource::layout() const {
  const std::lock_guard lock(mutex_);
  return layout_;
}

int SampleSource::max_channels() const {
  const std::optional<Sidecar> known = layout();
  return known ? static_cast<int>(known->channels.size()) : 1;
}

void SampleSource::set_layout(const Sidecar& sidecar) {
  const std::lock_guard lock(mutex_);
  layout_ = sidecar;
}

void SampleSource::start(BlockQueue& queue) {
  if (thread_.joinable()) return;
  queue_ = &queue;
  stop_.store(false, std::memory_order_release);
  finished_.store(false, std::memory_order_release);
  thread_ = std::thread([this] { thread_main(); });
}

void SampleSource::thread_main() {
  try {
    run();
  } catch (const std::exception& error) {  // nothing throws across threads
    post_event({std::numeric_limits<double>::quiet_NaN(), EventKind::Error, error.what()});
  }
  finished_.store(true, std::memory_order_release);
}

void SampleSource::stop() {
  stop_.store(true, std::memory_order_release);
  interrupt();
  if (thread_.joinable()) thread_.join();
}

SourceCounters SampleSource::counters() const {
  SourceCounters c;
  c.blocks_delivered = blocks_.load(std::memory_order_relaxed);
  c.samples_delivered = samples_.load(std::memory_order_relaxed);
  c.blocks_overflowed = overflowed_.load(std::memory_order_relaxed);
  kind_counters(c);
  return c;
}

std::vector<StreamEvent> SampleSource::take_events() {
  const std::lock_guard lock(mutex_);
  std::vector<StreamEvent> out;
  out.swap(events_);
  return out;
}

void SampleSource::post_event(StreamEvent event) {
  if (event.wall.empty()) event.wall = utc_now_iso8601();
  const std::lock_guard lock(mutex_);
  events_.push_back(std::move(event));
}

RawBlock* SampleSource::begin_block(bool wait) {
  for (;;) {
    if (RawBlock* block = queue_->begin_push()) return block;
    if (!wait || stop_requested()) return nullptr;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

RawBlock* SampleSource::begin_block_within(std::chrono::milliseconds max_wait) {
  const auto deadline = std::chrono::steady_clock::now() + max_wait;
  for (;;) {
    if (RawBlock* block = queue_->begin_push()) return block;
    if (stop_requested() || std::chrono::steady_clock::now() >= deadline) return nullptr;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

void SampleSource::end_block(RawBlock& block) {
  block.delivered = std::chrono::steady_clock::now();
  blocks_.fetch_add(1, std::memory_order_relaxed);
  samples_.fetch_add(static_cast<std::uint64_t>(block.rows), std::memory_order_relaxed);
  queue_->end_push();
}

void SampleSource::count_overflow(std::uint64_t first_sample) {
  const std::uint64_t count = overflowed_.fetch_add(1, std::memory_order_relaxed) + 1;
  // One event for the first overflow and then one per 100, so a stalled consumer cannot flood
  // the log; the counter holds the exact number.
  if (count == 1 || count % 100 == 0) {
    const Sidecar sidecar = layout().value_or(Sidecar{});
    const double rate = sidecar.sample_rate_hz > 0 ? sidecar.sample_rate_hz : 1.0;
    post_event({static_cast<double>(first_sample) / rate,
                EventKind::Overflow,
                "the consumer is behind: the queue is full and blocks are dropped",
                {{"blocks", count}}});
  }
}

}  // namespace oscilab::daq
