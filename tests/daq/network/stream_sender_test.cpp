#include "daq/network/stream_sender.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <future>
#include <map>
#include <mutex>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"
#include "daq/network/net_source.h"
#include "daq/network/stream_protocol.h"
#include "daq/network/tcp_socket.h"
#include "daq/sources/block_queue.h"
#include "tests/daq/stream_test_layout.h"

namespace oscilab::daq {
namespace {

using stream_protocol::FrameType;

constexpr double kRateHz = 512.0;
constexpr int kChannels = 2;
// A run that has not ended by then is hung: cancelled, and the test fails. Generous, for a
// loaded machine or a sanitizer build; the tests take well under a second each.
constexpr std::chrono::seconds kWatchdog{30};

// Rows of block i: 1 … max_rows, varying, so that first_sample is not a multiple of anything.
int rows_of(std::uint64_t block, int max_rows) {
  return 1 + static_cast<int>((block * 37u) % static_cast<std::uint64_t>(max_rows));
}

// The stored values of block i as bit patterns: any 64 bits, NaN payloads, infinities,
// subnormals and signed zeros included (seeded, so the receiver's side can recompute them).
std::vector<std::uint64_t> bits_of(std::uint64_t block, int rows) {
  std::mt19937_64 rng(0x5eed0000u + block);
  std::vector<std::uint64_t> bits(static_cast<std::size_t>(rows) * kChannels);
  for (std::uint64_t& b : bits) b = rng();
  if (block == 0) {  // the special values for sure, not only by chance
    bits[0] = std::bit_cast<std::uint64_t>(-0.0);
    bits[1] = 0x7ff0000000000000u;                       // +Inf
    if (bits.size() > 3) bits[2] = 0x7ff0000000000001u;  // a signalling NaN
    if (bits.size() > 3) bits[3] = 0x0000000000000001u;  // the smallest subnormal
  }
  return bits;
}

// first_sample of each of the first `count` blocks.
std::vector<std::uint64_t> first_samples(std::size_t count, int max_rows) {
  std::vector<std::uint64_t> first(count, 0);
  for (std::size_t i = 1; i < count; ++i) {
    first[i] = first[i - 1] + static_cast<std::uint64_t>(rows_of(i - 1, max_rows));
  }
  return first;
}

// A source of generated blocks (bits_of, rows_of) that waits for room in the queue and posts
// each block's events just before it publishes the block, as the rig and a replay do: `count`
// blocks then `after` (events with no block after them), or endless with count 0.
class TestSource final : public SampleSource {
 public:
  TestSource(std::size_t count, int max_rows,
             std::map<std::size_t, std::vector<StreamEvent>> events = {},
             std::vector<StreamEvent> after = {})
      : count_(count), max_rows_(max_rows), events_(std::move(events)), after_(std::move(after)) {
    set_layout(testing::two_channel_layout());
  }
  ~TestSource() override { stop(); }
  int max_block_rows() const override { return max_rows_; }
  std::string describe() const override { return "test source"; }
  bool ran() const { return ran_.load(); }

 private:
  void run() override {
    ran_.store(true);
    std::uint64_t first = 0;
    for (std::uint64_t i = 0; count_ == 0 || i < count_; ++i) {
      if (const auto e = events_.find(i); e != events_.end()) {
        for (const StreamEvent& event : e->second) post_event(event);
      }
      RawBlock* block = begin_block(true);
      if (block == nullptr) return;  // stop requested
      const int rows = rows_of(i, max_rows_);
      const std::vector<std::uint64_t> bits = bits_of(i, rows);
      for (std::size_t k = 0; k < bits.size(); ++k) {
        block->values[k] = std::bit_cast<double>(bits[k]);
      }
      block->sequence = i;
      block->first_sample = first;
      block->rows = rows;
      block->channels = kChannels;
      end_block(*block);
      first += static_cast<std::uint64_t>(rows);
    }
    for (const StreamEvent& event : after_) post_event(event);
  }

  std::size_t count_;
  int max_rows_;
  std::map<std::size_t, std::vector<StreamEvent>> events_;
  std::vector<StreamEvent> after_;
  std::atomic<bool> ran_{false};
};

// One frame as a receiver got it, on its `connection`-th connection (from 1).
struct Received {
  int connection = 0;
  FrameType type = FrameType::Bye;
  std::string stream_id;  // HELLO
  Sidecar sidecar;        // HELLO
  std::uint64_t sequence = 0, first_sample = 0;
  int rows = 0, channels = 0;
  std::vector<std::uint64_t> bits;  // DATA: the values' bit patterns
  StreamEvent event;                // EVENT
};

// A receiver written from docs/stream-protocol.md on 127.0.0.1 and an ephemeral port, on its own
// thread: it logs every frame, serves one sender after another until a BYE, and can be told to
// drop the connection after a given block (and to stop listening then), to cancel a token after
// a given block, or never to read at all.
class TestReceiver {
 public:
  struct Options {
    std::optional<std::uint64_t> drop_after;  // close the connection after this DATA sequence
    bool stop_listening_on_drop = false;
    std::optional<std::uint64_t> cancel_after;  // cancel `cancel` after this DATA sequence
    CancelToken cancel;
    bool read = true;  // false: accept, then never read
  };

  explicit TestReceiver(Options options)
      : options_(std::move(options)), listener_(TcpSocket::listen_on("127.0.0.1", 0)) {
    port_ = listener_.local_port();
    thread_ = std::thread([this] { serve(); });
  }
  ~TestReceiver() {
    {
      const std::lock_guard lock(mutex_);
      stop_ = true;
    }
    changed_.notify_all();
    thread_.join();
  }

  std::uint16_t port() const { return port_; }
  // Waits until the connection was dropped as told.
  void wait_dropped() {
    std::unique_lock lock(mutex_);
    expect_within_watchdog(
        lock, [&] { return dropped_ || stop_; }, "the receiver dropped the connection as told");
  }
  // Waits until a sender was accepted.
  void wait_accepted() {
    std::unique_lock lock(mutex_);
    expect_within_watchdog(
        lock, [&] { return connections_ > 0; }, "a sender was accepted");
  }
  // Waits until the stream ended (BYE) or the receiver gave up; the frames received.
  std::vector<Received> frames_at_end() {
    std::unique_lock lock(mutex_);
    expect_within_watchdog(
        lock, [&] { return ended_; }, "the stream ended (BYE)");
    return frames_;
  }
  std::string error() {
    const std::lock_guard lock(mutex_);
    return error_;
  }

 private:
  bool stopping() {
    const std::lock_guard lock(mutex_);
    return stop_;
  }
  void end(const std::string& error = {}) {
    {
      const std::lock_guard lock(mutex_);
      ended_ = true;
      error_ = error;
    }
    changed_.notify_all();
  }

  void serve() {
    while (!stopping()) {
      if (!listener_.valid()) return end();
      TcpSocket peer = listener_.accept_for(50);
      if (!peer.valid()) continue;
      int connection = 0;
      {
        const std::lock_guard lock(mutex_);
        connection = ++connections_;
      }
      changed_.notify_all();
      if (!options_.read) {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [&] { return stop_; });
        return;
      }
      if (read_connection(peer, connection)) return;
    }
  }

  // One connection; true when the stream ended (BYE, an error, or told to stop).
  bool read_connection(TcpSocket& peer, int connection) {
    stream_protocol::FrameDecoder decoder;
    std::vector<std::uint8_t> buffer(1u << 16);
    for (;;) {
      if (stopping()) return true;
      const long got = peer.receive_for(buffer.data(), buffer.size(), 50);
      if (got == -1) continue;
      if (got <= 0) return false;  // the sender went away: wait for it to come back
      decoder.feed(buffer.data(), static_cast<std::size_t>(got));
      stream_protocol::Frame frame;
      while (decoder.next(frame)) {
        Received r;
        r.connection = connection;
        r.type = frame.type;
        if (frame.hello) {
          r.stream_id = frame.hello->stream_id;
          r.sidecar = frame.hello->sidecar;
        }
        if (frame.event) r.event = *frame.event;
        if (frame.type == FrameType::Data) {
          r.sequence = frame.sequence;
          r.first_sample = frame.first_sample;
          r.rows = frame.rows;
          r.channels = frame.channels;
          for (int i = 0; i < frame.rows * frame.channels; ++i) {
            r.bits.push_back(
                std::bit_cast<std::uint64_t>(stream_protocol::read_f64_le(frame.data + 8 * i)));
          }
        }
        {
          const std::lock_guard lock(mutex_);
          frames_.push_back(r);
        }
        if (frame.type == FrameType::Bye) {
          end();
          return true;
        }
        if (frame.type != FrameType::Data) continue;
        if (options_.cancel_after && frame.sequence == *options_.cancel_after) {
          options_.cancel.cancel();
        }
        if (options_.drop_after && frame.sequence == *options_.drop_after) {
          if (options_.stop_listening_on_drop) listener_.close();
          peer.close();
          {
            const std::lock_guard lock(mutex_);
            dropped_ = true;
          }
          changed_.notify_all();
          return false;
        }
      }
      if (!decoder.error().empty()) {
        end(decoder.error());
        return true;
      }
    }
  }

  // The watchdog only guards against a hang: a failure names what never happened.
  template <typename Predicate>
  void expect_within_watchdog(std::unique_lock<std::mutex>& lock, Predicate done,
                              const char* what) {
    if (!changed_.wait_for(lock, kWatchdog, done)) {
      ADD_FAILURE() << "never happened within the watchdog: " << what;
    }
  }

  Options options_;
  TcpSocket listener_;
  std::uint16_t port_ = 0;
  std::thread thread_;
  std::mutex mutex_;  // guards what follows
  std::condition_variable changed_;
  bool stop_ = false, dropped_ = false, ended_ = false;
  int connections_ = 0;
  std::vector<Received> frames_;
  std::string error_;
};

// Runs the sender on its own thread; the result, or a failure when it hangs (then cancelled).
struct SenderRun {
  SenderRun(StreamSender& sender, SampleSource& source, CancelToken cancel,
            ProgressFn progress = {})
      : cancel_(cancel),
        future_(std::async(std::launch::async, [&sender, &source, progress, cancel] {
          return sender.run(source, progress, cancel);
        })) {}
  StreamSender::Result result() {
    const bool ended = future_.wait_for(kWatchdog) == std::future_status::ready;
    if (!ended) cancel_.cancel();
    StreamSender::Result r = future_.get();
    EXPECT_TRUE(ended) << "the sender hung";
    return r;
  }
  CancelToken cancel_;
  std::future<StreamSender::Result> future_;
};

// Polls a condition another thread makes true (the sender's counters have no notification).
bool eventually(const std::function<bool()>& condition) {
  const auto deadline = std::chrono::steady_clock::now() + kWatchdog;
  while (!condition()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

StreamSender::Options to(std::uint16_t port) {
  StreamSender::Options o;
  o.port = port;
  return o;
}

// Checks a DATA frame against the block the source generated under its sequence number.
void expect_block_as_generated(const Received& r, const std::vector<std::uint64_t>& first,
                               int max_rows) {
  ASSERT_LT(r.sequence, first.size());
  EXPECT_EQ(r.first_sample, first[r.sequence]) << "block " << r.sequence;
  EXPECT_EQ(r.rows, rows_of(r.sequence, max_rows)) << "block " << r.sequence;
  EXPECT_EQ(r.channels, kChannels);
  EXPECT_TRUE(r.bits == bits_of(r.sequence, r.rows)) << "block " << r.sequence << " differs";
}

TEST(StreamSender, SendsEverySampleInOrderBitForBitWithEachEventBeforeItsBlock) {
  constexpr std::size_t kBlocks = 300;
  constexpr int kMaxRows = 64;
  const std::vector<std::uint64_t> first = first_samples(kBlocks, kMaxRows);
  const auto at = [&](std::size_t block) { return static_cast<double>(first[block]) / kRateHz; };
  std::map<std::size_t, std::vector<StreamEvent>> events;
  events[0] = {{at(0), EventKind::Level, "rest", {{"f0_n", 0.0}, {"frequency_hz", 9.0}}}};
  events[10] = {{at(10), EventKind::Level, "up", {{"f0_n", 0.5}, {"frequency_hz", 9.0}}},
                {at(10), EventKind::Mark, "operator"}};
  events[20] = {{at(20), EventKind::Alarm, "not the receiver's business"}};
  events[30] = {{at(30), EventKind::Invalid, "sensor", {{"from_s", at(30)}, {"to_s", at(31)}}}};
  events[150] = {{at(150), EventKind::Overflow, "not forwarded"},
                 {at(150), EventKind::Discontinuity, "seek"}};
  events[299] = {{at(299), EventKind::Mark, "last block"}};
  const std::vector<StreamEvent> after = {{at(299) + 1.0, EventKind::Mark, "after the last block"}};
  TestSource source(kBlocks, kMaxRows, events, after);
  TestReceiver receiver({});
  StreamSender::Options options = to(receiver.port());
  options.stream_id = "test-1";
  options.expected_samples = first.back() + rows_of(kBlocks - 1, kMaxRows);
  StreamSender sender(options);
  std::vector<double> fractions;  // only touched on the sender's thread until it returns
  SenderRun run(sender, source, {}, [&](double f) { fractions.push_back(f); });
  const StreamSender::Result result = run.result();
  const std::vector<Received> frames = receiver.frames_at_end();
  ASSERT_EQ(receiver.error(), "");

  EXPECT_EQ(result.status, StreamSender::Status::Ok);
  EXPECT_EQ(result.stream_id, "test-1");
  EXPECT_EQ(result.counters.blocks_sent, kBlocks);
  EXPECT_EQ(result.counters.blocks_lost, 0u);
  EXPECT_EQ(result.counters.reconnections, 0u);
  // HELLO first, with the source's sidecar; BYE last; one connection.
  ASSERT_GE(frames.size(), 2u);
  ASSERT_EQ(frames.front().type, FrameType::Hello);
  EXPECT_EQ(frames.front().stream_id, "test-1");
  EXPECT_EQ(layout_difference(testing::two_channel_layout(), frames.front().sidecar), "");
  EXPECT_EQ(frames.back().type, FrameType::Bye);
  std::vector<std::size_t> data_index;  // frame index of each block's DATA
  std::vector<std::pair<std::size_t, StreamEvent>> received_events;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(frames[i].connection, 1);
    if (i > 0) {
      EXPECT_NE(frames[i].type, FrameType::Hello);
    }
    if (frames[i].type == FrameType::Data) {
      // Every block, in order, each sample bit for bit.
      ASSERT_EQ(frames[i].sequence, data_index.size());
      expect_block_as_generated(frames[i], first, kMaxRows);
      data_index.push_back(i);
    }
    if (frames[i].type == FrameType::Event) received_events.emplace_back(i, frames[i].event);
  }
  EXPECT_EQ(data_index.size(), kBlocks);
  // The forwarded kinds only, in the order posted, each before the block that reaches its time.
  std::vector<std::string> expected_texts = {
      "rest", "up", "operator", "sensor", "seek", "last block", "after the last block"};
  ASSERT_EQ(received_events.size(), expected_texts.size());
  for (std::size_t k = 0; k < received_events.size(); ++k) {
    const auto& [index, event] = received_events[k];
    EXPECT_EQ(event.text, expected_texts[k]);
    // Only "before its block" is promised: a source may run ahead of the sender, so an event can
    // come before earlier blocks too. One posted after the last block still comes before BYE.
    const auto block = std::lower_bound(first.begin(), first.end(),
                                        static_cast<std::uint64_t>(event.t_s * kRateHz));
    if (block != first.end()) {
      EXPECT_LT(index, data_index[static_cast<std::size_t>(block - first.begin())])
          << "event \"" << event.text << "\" after its block";
    }
  }
  EXPECT_EQ(received_events[0].second.data["f0_n"], 0.0);
  EXPECT_EQ(received_events[3].second.data["to_s"], at(31));
  // Progress: one report per block, never backwards, ending at 1.
  ASSERT_EQ(fractions.size(), kBlocks);
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  EXPECT_EQ(fractions.back(), 1.0);
}

TEST(StreamSender, TheProjectsReceiverGetsEverySampleAndEventAsSent) {
  constexpr std::size_t kBlocks = 200;
  constexpr int kMaxRows = 128;
  const std::vector<std::uint64_t> first = first_samples(kBlocks, kMaxRows);
  const double level_s = static_cast<double>(first[50]) / kRateHz;
  TestSource source(
      kBlocks, kMaxRows,
      {{50, {{level_s, EventKind::Level, "up", {{"f0_n", 1.0}, {"frequency_hz", 9.0}}}}}});
  NetSource net(NetSource::Options{});
  BlockQueue queue(256, net.max_block_rows(), net.max_channels());
  net.start(queue);
  StreamSender sender(to(net.port()));
  SenderRun run(sender, source, {});

  std::vector<Received> blocks;
  const bool ended = eventually([&] {
    for (RawBlock* b = queue.front(); b != nullptr; b = queue.front()) {
      Received r;
      r.sequence = b->sequence;
      r.first_sample = b->first_sample;
      r.rows = b->rows;
      r.channels = b->channels;
      for (int i = 0; i < b->rows * b->channels; ++i) {
        r.bits.push_back(std::bit_cast<std::uint64_t>(b->values[static_cast<std::size_t>(i)]));
      }
      blocks.push_back(std::move(r));
      queue.pop();
    }
    return net.finished() && queue.size() == 0;
  });
  const StreamSender::Result result = run.result();
  net.stop();
  ASSERT_TRUE(ended) << "the receiver never saw the BYE";
  EXPECT_EQ(result.status, StreamSender::Status::Ok);
  ASSERT_EQ(blocks.size(), kBlocks);
  for (std::size_t i = 0; i < kBlocks; ++i) {
    EXPECT_EQ(blocks[i].sequence, i);
    expect_block_as_generated(blocks[i], first, kMaxRows);
  }
  ASSERT_TRUE(net.layout());
  EXPECT_EQ(layout_difference(testing::two_channel_layout(), *net.layout()), "");
  std::vector<std::string> kinds;
  for (const StreamEvent& e : net.take_events()) {
    kinds.push_back(e.kind_name());
    if (e.kind == EventKind::Level) {
      EXPECT_EQ(e.t_s, level_s);
      EXPECT_EQ(e.data["f0_n"], 1.0);
    }
  }
  EXPECT_EQ(kinds,
            (std::vector<std::string>{"connected", "level", "source-ended", "disconnected"}));
  EXPECT_EQ(net.counters().samples_delivered, first.back() + rows_of(kBlocks - 1, kMaxRows));
}

TEST(StreamSender, ReconnectsWithTheSameStreamIdAndGoesOnSoTheReceiverSeesTheGap) {
  constexpr std::size_t kBlocks = 400;
  constexpr int kMaxRows = 64;
  constexpr std::uint64_t kDropAfter = 49;
  const std::vector<std::uint64_t> first = first_samples(kBlocks, kMaxRows);
  TestSource source(kBlocks, kMaxRows);
  TestReceiver::Options drop;
  drop.drop_after = kDropAfter;
  TestReceiver receiver(drop);
  StreamSender::Options options = to(receiver.port());
  options.expected_samples = first.back() + rows_of(kBlocks - 1, kMaxRows);
  StreamSender sender(options);
  std::uint64_t reports = 0;
  // The sender holds after block 49 until the receiver has dropped the connection, so that the
  // break comes while most of the stream is still to be sent.
  SenderRun run(sender, source, {}, [&](double) {
    if (++reports == kDropAfter + 1) receiver.wait_dropped();
  });
  const StreamSender::Result result = run.result();
  const std::vector<Received> frames = receiver.frames_at_end();
  ASSERT_EQ(receiver.error(), "");

  EXPECT_EQ(result.status, StreamSender::Status::Ok);
  EXPECT_EQ(result.counters.reconnections, 1u);
  EXPECT_GE(result.counters.blocks_lost, 1u);  // the block whose send failed
  EXPECT_EQ(result.counters.blocks_sent + result.counters.blocks_lost, kBlocks);
  // Connection 1: HELLO, blocks 0…49. Connection 2: the same stream_id, then the blocks from
  // where the stream had gone on to, with their own sequence numbers and sample indices.
  std::vector<std::vector<const Received*>> data(3);
  std::vector<std::string> ids;
  for (const Received& r : frames) {
    ASSERT_TRUE(r.connection == 1 || r.connection == 2);
    if (r.type == FrameType::Hello) ids.push_back(r.stream_id);
    if (r.type == FrameType::Data) data[static_cast<std::size_t>(r.connection)].push_back(&r);
  }
  ASSERT_EQ(ids.size(), 2u);
  EXPECT_EQ(ids[0], result.stream_id);
  EXPECT_EQ(ids[1], result.stream_id);
  EXPECT_EQ(frames[0].type, FrameType::Hello);
  ASSERT_EQ(data[1].size(), kDropAfter + 1);
  for (std::size_t i = 0; i < data[1].size(); ++i) EXPECT_EQ(data[1][i]->sequence, i);
  ASSERT_FALSE(data[2].empty());
  const std::uint64_t resumed = data[2].front()->sequence;
  const std::uint64_t gap_blocks = resumed - (kDropAfter + 1);
  EXPECT_GE(gap_blocks, result.counters.blocks_lost);  // plus any sent into the dropped one
  EXPECT_EQ(data[2].size(), kBlocks - resumed);
  for (std::size_t i = 0; i < data[2].size(); ++i) EXPECT_EQ(data[2][i]->sequence, resumed + i);
  for (int c = 1; c <= 2; ++c) {
    for (const Received* r : data[static_cast<std::size_t>(c)]) {
      expect_block_as_generated(*r, first, kMaxRows);
    }
  }
  // The gap in samples is exactly the lost blocks' rows: the sample clock went on.
  EXPECT_EQ(data[2].front()->first_sample - (data[1].back()->first_sample + data[1].back()->rows),
            first[resumed] - first[kDropAfter + 1]);
  EXPECT_EQ(frames.back().type, FrameType::Bye);
  EXPECT_EQ(frames.back().connection, 2);
}

TEST(StreamSender, ReportsNoReceiverNamingHostAndPortWithoutStartingTheSource) {
  std::uint16_t port = 0;
  {
    const TcpSocket probe = TcpSocket::listen_on("127.0.0.1", 0);
    port = probe.local_port();
  }  // closed: nobody listens there now
  TestSource source(0, 16);
  StreamSender sender(to(port));
  const StreamSender::Result result = SenderRun(sender, source, {}).result();
  EXPECT_EQ(result.status, StreamSender::Status::NoReceiver);
  EXPECT_NE(result.message.find("connect to 127.0.0.1:" + std::to_string(port)), std::string::npos)
      << result.message;
  EXPECT_FALSE(source.ran());
  EXPECT_EQ(result.counters.blocks_sent, 0u);
  EXPECT_FALSE(result.counters.connected);
}

TEST(StreamSender, GivesUpNamingHostAndPortWhenTheReceiverIsGoneForGood) {
  TestSource source(0, 16);  // endless: only the receiver's absence ends this run
  TestReceiver::Options drop;
  drop.drop_after = 9;
  drop.stop_listening_on_drop = true;
  TestReceiver receiver(drop);
  StreamSender::Options options = to(receiver.port());
  options.retry_s = 0.3;
  options.expected_samples = 1u << 30;
  StreamSender sender(options);
  std::uint64_t reports = 0;
  SenderRun run(sender, source, {}, [&](double) {
    if (++reports == 10) receiver.wait_dropped();
  });
  const StreamSender::Result result = run.result();
  EXPECT_EQ(result.status, StreamSender::Status::ReceiverGone);
  EXPECT_EQ(result.message, "127.0.0.1:" + std::to_string(receiver.port()) +
                                ": the receiver is gone (no connection for 0.300000 s)");
  EXPECT_EQ(result.counters.reconnections, 0u);
  EXPECT_TRUE(source.finished());  // stopped
}

TEST(StreamSender, CancelEndsTheStreamWithByeAndStopsTheSource) {
  TestSource source(0, 64);  // endless: only the cancel ends this run
  TestReceiver::Options options;
  options.cancel_after = 100;
  TestReceiver receiver(options);
  StreamSender sender(to(receiver.port()));
  const StreamSender::Result result = SenderRun(sender, source, options.cancel).result();
  const std::vector<Received> frames = receiver.frames_at_end();
  EXPECT_EQ(result.status, StreamSender::Status::Cancelled);
  ASSERT_FALSE(frames.empty());
  EXPECT_EQ(frames.back().type, FrameType::Bye);
  std::uint64_t blocks = 0;
  for (const Received& r : frames) {
    if (r.type == FrameType::Data) {
      EXPECT_EQ(r.sequence, blocks++);
    }
  }
  EXPECT_GT(blocks, 100u);
  EXPECT_EQ(result.counters.blocks_sent, blocks);  // every block sent arrived
  EXPECT_TRUE(source.finished());
}

TEST(StreamSender, CancelReturnsWhileTheReceiverStopsReading) {
  TestSource source(0, 1024);  // 16 KiB blocks, endless
  TestReceiver::Options options;
  options.read = false;
  TestReceiver receiver(options);
  StreamSender::Options sender_options = to(receiver.port());
  sender_options.queue_blocks = 4;
  StreamSender sender(sender_options);
  CancelToken cancel;
  SenderRun run(sender, source, cancel);
  receiver.wait_accepted();
  // Held up: the socket buffers are full, the sender sits on a block, the queue behind it full.
  EXPECT_TRUE(eventually([&] {
    return source.counters().blocks_delivered >=
           sender.counters().blocks_sent + 1 + sender_options.queue_blocks;
  })) << "the sender was never held up with its queue full";
  cancel.cancel();
  const StreamSender::Result result = run.result();
  EXPECT_EQ(result.status, StreamSender::Status::Cancelled);
  EXPECT_TRUE(source.finished());
}

TEST(StreamSender, CancelEndsTheWaitForAReceiverThatWentAway) {
  TestSource source(0, 16);
  TestReceiver::Options drop;
  drop.drop_after = 9;
  drop.stop_listening_on_drop = true;
  TestReceiver receiver(drop);
  StreamSender::Options options = to(receiver.port());
  options.retry_s = 3600.0;  // the run could only end by cancel within the watchdog
  StreamSender sender(options);
  CancelToken cancel;
  SenderRun run(sender, source, cancel);
  receiver.wait_dropped();
  // The sender has noticed the break: it is trying to reconnect.
  EXPECT_TRUE(eventually([&] {
    const StreamSender::Counters c = sender.counters();
    return c.blocks_sent > 0 && !c.connected;
  })) << "the sender never noticed the break";
  cancel.cancel();
  const StreamSender::Result result = run.result();
  EXPECT_EQ(result.status, StreamSender::Status::Cancelled);
  EXPECT_EQ(result.counters.reconnections, 0u);
  EXPECT_TRUE(source.finished());
}

TEST(StreamSender, ThrowsInputErrorNamingTheOptionOnInvalidOptions) {
  StreamSender::Options no_port;
  EXPECT_THROW(StreamSender{no_port}, InputError);
  StreamSender::Options no_host = to(5025);
  no_host.host.clear();
  EXPECT_THROW(StreamSender{no_host}, InputError);
  try {
    StreamSender::Options no_queue = to(5025);
    no_queue.queue_blocks = 0;
    StreamSender sender(no_queue);
    FAIL() << "a queue of 0 blocks accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("queue_blocks"), std::string::npos);
  }
}

}  // namespace
}  // namespace oscilab::daq
