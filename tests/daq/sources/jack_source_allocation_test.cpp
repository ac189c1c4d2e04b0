// The JACK path allocates nothing once it runs: the process callback (the real-time thread, which
// must never allocate) and the source's thread draining its ring through the resampler into the
// queue. This binary replaces the global operator new and counts the allocations of every thread
// but the test's own (which drains the queue) while a steady stream passes through a real jackd
// (dummy backend); the test player's process callback is a JACK client in this process too and
// is counted with them.
#include <thread>

#include <gtest/gtest.h>

#include "daq/sources/block_queue.h"
#include "tests/allocation_counter.h"
#include "tests/daq/sources/jack_test_helpers.h"

namespace oscilab::daq {
namespace {

using oscilab::testing::allocation_counter;
using testing::jack_options;
using testing::JackTestPlayer;
using testing::JackTestServer;
using testing::kRateHz;

// Takes blocks off the queue until `samples` more have come (a minute at most).
std::uint64_t drain(BlockQueue& queue, std::uint64_t samples) {
  std::uint64_t taken = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (taken < samples && std::chrono::steady_clock::now() < deadline) {
    while (RawBlock* block = queue.front()) {
      taken += static_cast<std::uint64_t>(block->rows);
      queue.pop();
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return taken;
}

TEST(JackSourceAllocations, TheProcessCallbackAndTheResamplerAllocateNothingOnceRunning) {
  JackTestServer server;
  JackTestPlayer player(server.name(), 2);
  player.play_sines({{0.5, 9.0, 0.3}, {0.25, 37.0, -1.1}});
  auto source = std::make_unique<JackSource>(jack_options(server, player));
  BlockQueue queue(1024, source->max_block_rows(), 2);
  source->start(queue);
  ASSERT_GE(drain(queue, 2 * static_cast<std::uint64_t>(kRateHz)), 2 * kRateHz) << "warm-up";
  // A window of 1 s of stream with no fault: an xrun (which a loaded machine can cause) is an
  // event, and an event's text is allocated; a window it falls in is measured again, up to 30
  // times. (Under ASan beside another test, ten windows of 2 s once all had an xrun.)
  std::uint64_t counted = 0, seen = 0, windows = 0, faulty_windows = 0;
  while (windows < 30) {
    ++windows;
    const SourceCounters before = source->counters();
    allocation_counter.start(std::this_thread::get_id());
    counted = drain(queue, static_cast<std::uint64_t>(kRateHz));
    seen = allocation_counter.stop();
    const SourceCounters after = source->counters();
    if (after.jack.xruns == before.jack.xruns &&
        after.jack.dropped_frames == before.jack.dropped_frames &&
        after.jack.server_losses == before.jack.server_losses &&
        after.jack.port_disconnections == 0) {
      break;
    }
    ++faulty_windows;
  }
  source->stop();
  ASSERT_LT(faulty_windows, windows) << "no window without an xrun in " << windows;
  EXPECT_GE(counted, kRateHz) << "1 s of stream passed while counting";
  EXPECT_EQ(seen, 0u) << "the first by thread \"" << allocation_counter.first_thread_name << "\"";
}

}  // namespace
}  // namespace oscilab::daq
