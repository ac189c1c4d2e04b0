#include "daq/network/stream_sender.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <thread>

#include "analysis/common/input_error.h"
#include "daq/network/stream_protocol.h"
#include "daq/sources/block_queue.h"

namespace oscilab::daq {
namespace {

constexpr int kSendPollMs = 50;  // how long a send waits for the receiver before looking at cancel
constexpr std::chrono::milliseconds kRetryEvery{200};
constexpr std::chrono::milliseconds kIdle{1};  // waiting for the source's next block

// Events the receiver needs to analyse and record the stream as operated.
bool forwarded(EventKind kind) {
  return kind == EventKind::Level || kind == EventKind::Mark || kind == EventKind::Discontinuity ||
         kind == EventKind::Invalid;
}

std::string random_stream_id() {
  std::random_device entropy;
  return "oscilab-" + std::to_string(entropy()) + std::to_string(entropy());
}

// Sleeps for `duration` unless cancelled meanwhile.
void pause_for(std::chrono::milliseconds duration, const CancelToken& cancel) {
  const auto until = std::chrono::steady_clock::now() + duration;
  while (!cancel.cancelled() && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::min(duration, std::chrono::milliseconds(10)));
  }
}

// Stops the source however run() is left: its thread writes into run()'s queue.
class StopOnExit {
 public:
  explicit StopOnExit(SampleSource& source) : source_(source) {}
  ~StopOnExit() { source_.stop(); }
  StopOnExit(const StopOnExit&) = delete;
  StopOnExit& operator=(const StopOnExit&) = delete;

 private:
  SampleSource& source_;
};

}  // namespace

StreamSender::StreamSender(Options options) : options_(std::move(options)) {
  if (options_.host.empty()) throw InputError("stream sender: host: empty");
  if (options_.port == 0) throw InputError("stream sender: port: 0 (1..65535 required)");
  if (std::isnan(options_.retry_s)) throw InputError("stream sender: retry_s: NaN");
  if (options_.queue_blocks < 1) throw InputError("stream sender: queue_blocks: 0");
}

std::string StreamSender::address() const {
  return options_.host + ":" + std::to_string(options_.port);
}

StreamSender::Counters StreamSender::counters() const {
  Counters c;
  c.blocks_sent = blocks_sent_.load(std::memory_order_relaxed);
  c.blocks_lost = blocks_lost_.load(std::memory_order_relaxed);
  c.reconnections = reconnections_.load(std::memory_order_relaxed);
  c.connected = connected_.load(std::memory_order_relaxed);
  return c;
}

StreamSender::Result StreamSender::run(SampleSource& source, const ProgressFn& progress,
                                       const CancelToken& cancel) {
  const std::optional<Sidecar> layout = source.layout();
  if (!layout) {
    throw InputError("stream sender: " + source.describe() +
                     ": the stream's layout is not known before its first block");
  }
  blocks_sent_ = 0;
  blocks_lost_ = 0;
  reconnections_ = 0;
  Result result;
  stream_protocol::Hello hello;
  hello.stream_id = options_.stream_id.empty() ? random_stream_id() : options_.stream_id;
  hello.sidecar = *layout;
  result.stream_id = hello.stream_id;
  hello_frame_.clear();
  stream_protocol::append_hello(hello, hello_frame_);
  const auto finish = [&](Status status, std::string message = {}) {
    socket_.close();
    connected_ = false;
    result.status = status;
    result.message = std::move(message);
    result.counters = counters();
    return result;
  };

  try {
    socket_ = TcpSocket::connect_to(options_.host, options_.port);
  } catch (const InputError& error) {
    return finish(Status::NoReceiver, error.what());
  }
  connected_ = true;
  const std::string gone = address() + ": the receiver is gone (no connection for " +
                           std::to_string(options_.retry_s) + " s)";
  Sent outcome = deliver(hello_frame_, cancel);

  BlockQueue queue(options_.queue_blocks, source.max_block_rows(), source.max_channels());
  std::vector<std::uint8_t> frame;
  {
    const StopOnExit stop_source(source);
    if (outcome != Sent::Cancelled && outcome != Sent::ReceiverGone) source.start(queue);
    const auto send_events = [&] {
      for (const StreamEvent& event : source.take_events()) {
        if (!forwarded(event.kind)) continue;
        frame.clear();
        stream_protocol::append_event(event, frame);
        outcome = deliver(frame, cancel);
        if (outcome == Sent::Cancelled || outcome == Sent::ReceiverGone) return;
      }
    };
    while (outcome != Sent::Cancelled && outcome != Sent::ReceiverGone) {
      if (cancel.cancelled()) {
        outcome = Sent::Cancelled;
        break;
      }
      // The block first, then the events: a source posts an event before it publishes the block
      // that reaches the event's time, so the receiver gets every event before its block.
      RawBlock* block = queue.front();
      send_events();
      if (outcome == Sent::Cancelled || outcome == Sent::ReceiverGone) break;
      if (block == nullptr) {
        if (source.finished() && queue.size() == 0) {
          send_events();  // any posted after the last block
          break;
        }
        std::this_thread::sleep_for(kIdle);
        continue;
      }
      frame.clear();
      stream_protocol::append_data(block->sequence, block->first_sample, block->rows,
                                   block->channels, block->values.data(), frame);
      const std::uint64_t end_sample =
          block->first_sample + static_cast<std::uint64_t>(block->rows);
      queue.pop();
      outcome = deliver(frame, cancel);
      if (outcome == Sent::Yes) blocks_sent_.fetch_add(1, std::memory_order_relaxed);
      if (outcome == Sent::LostReconnected) blocks_lost_.fetch_add(1, std::memory_order_relaxed);
      if (progress && options_.expected_samples > 0) {
        progress(std::min(
            1.0, static_cast<double>(end_sample) / static_cast<double>(options_.expected_samples)));
      }
    }
  }

  if (outcome == Sent::ReceiverGone) return finish(Status::ReceiverGone, gone);
  if (socket_.valid()) {
    // A slow receiver is waited for; one that stopped reading holds a cancelled run one poll
    // period at most.
    frame.clear();
    stream_protocol::append_bye(frame);
    send_frame(frame, cancel);
  }
  return finish(outcome == Sent::Cancelled ? Status::Cancelled : Status::Ok);
}

StreamSender::Sent StreamSender::deliver(const std::vector<std::uint8_t>& frame,
                                         const CancelToken& cancel) {
  const Sent sent = socket_.valid() ? send_frame(frame, cancel) : Sent::ReceiverGone;
  if (sent != Sent::ReceiverGone) return sent;
  return reconnect(cancel);
}

StreamSender::Sent StreamSender::send_frame(const std::vector<std::uint8_t>& frame,
                                            const CancelToken& cancel) {
  std::size_t done = 0;
  while (done < frame.size()) {
    const long sent = socket_.send_for(frame.data() + done, frame.size() - done, kSendPollMs);
    if (sent == -1) {
      if (!cancel.cancelled()) continue;
      if (done > 0) {  // the receiver would read a frame cut short: no more frames on this one
        socket_.close();
        connected_ = false;
      }
      return Sent::Cancelled;
    }
    if (sent < 0) {
      socket_.close();
      connected_ = false;
      return Sent::ReceiverGone;
    }
    done += static_cast<std::size_t>(sent);
  }
  return Sent::Yes;
}

StreamSender::Sent StreamSender::reconnect(const CancelToken& cancel) {
  // The receiver went away: try again for up to retry_s, same stream_id, so that it sees what was
  // lost meanwhile as a gap.
  socket_.close();
  connected_ = false;
  const auto give_up =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(options_.retry_s);
  while (!cancel.cancelled() && std::chrono::steady_clock::now() < give_up) {
    try {
      socket_ = TcpSocket::connect_to(options_.host, options_.port);
      connected_ = true;
      const Sent greeted = send_frame(hello_frame_, cancel);
      if (greeted == Sent::Yes) {
        reconnections_.fetch_add(1, std::memory_order_relaxed);
        return Sent::LostReconnected;  // this frame is lost; the next goes to the new connection
      }
      socket_.close();  // no frame may follow on a connection not greeted
      connected_ = false;
      if (greeted == Sent::Cancelled) return greeted;
    } catch (const InputError&) {
    }
    pause_for(kRetryEvery, cancel);
  }
  return cancel.cancelled() ? Sent::Cancelled : Sent::ReceiverGone;
}

}  // namespace oscilab::daq
