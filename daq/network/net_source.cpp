#include "daq/network/net_source.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "daq/network/stream_protocol.h"

namespace oscilab::daq {
namespace {

constexpr int kPollMs = 50;  // how often a waiting thread looks at its stop flag
constexpr std::chrono::milliseconds kBackpressure{2000};
// The longest gap a DATA frame may open in its stream, s. The reference sender resumes after a
// break within --retry (10 s by default); a sender away longer starts a new stream (another
// stream_id), placed after the last sample. A larger jump is refused: its samples would move the
// stream clock (a first_sample of 2^63 is 1.8e16 s at 512 Hz) and its gap be written as NaN.
constexpr double kMaxGapS = 600.0;
// And at most this many samples (600 s up to 1.7 kHz): the chain runs through a gap sample by
// sample (NaN rows in the recording, the derived filters on zeros), about 10^5 samples a second,
// so a 590 s gap at 100 kHz held the recorder up for ten minutes.
constexpr double kMaxGapSamples = 1 << 20;

// The most samples a DATA frame may open as a gap at `rate_hz`.
double max_gap_samples(double rate_hz) { return std::min(kMaxGapS * rate_hz, kMaxGapSamples); }

}  // namespace

std::string layout_difference(const Sidecar& expected, const Sidecar& offered) {
  if (std::abs(expected.sample_rate_hz - offered.sample_rate_hz) >
      1e-9 * std::abs(expected.sample_rate_hz)) {
    return "sample rate " + std::to_string(offered.sample_rate_hz) + " Hz, expected " +
           std::to_string(expected.sample_rate_hz) + " Hz";
  }
  if (expected.channels.size() != offered.channels.size()) {
    return std::to_string(offered.channels.size()) + " channels, expected " +
           std::to_string(expected.channels.size());
  }
  for (std::size_t i = 0; i < expected.channels.size(); ++i) {
    const ChannelInfo& e = expected.channels[i];
    const ChannelInfo& o = offered.channels[i];
    const std::string where = "channel " + std::to_string(i) + " (\"" + e.name + "\"): ";
    if (e.name != o.name) return where + "named \"" + o.name + "\"";
    if (e.role != o.role || e.quantity != o.quantity) {
      return where + "role/quantity " + to_string(o.role) + "/" + to_string(o.quantity) +
             ", expected " + to_string(e.role) + "/" + to_string(e.quantity);
    }
    if (e.unit != o.unit || e.scale != o.scale || e.offset != o.offset) {
      return where + "calibration " + std::to_string(o.scale) + " " + o.unit + " + " +
             std::to_string(o.offset) + ", expected " + std::to_string(e.scale) + " " + e.unit +
             " + " + std::to_string(e.offset);
    }
  }
  return "";
}

std::string NetSource::sequence_problem(std::uint64_t sequence, double rate_hz) const {
  // Every block holds at least one row, so a stream that opens a gap of at most kMaxGapS skips at
  // most that many samples' worth of blocks. A sequence further ahead is refused: the blocks it
  // skips would be counted lost and the monitor would wait on them.
  const std::uint64_t expected = next_sequence_ - static_cast<std::uint64_t>(sequence_offset_);
  const double max_ahead = std::ceil(max_gap_samples(rate_hz));
  if (sequence <= expected || static_cast<double>(sequence - expected) <= max_ahead) return "";
  char text[200];
  std::snprintf(text, sizeof text,
                "DATA frame refused: sequence %llu is %llu blocks past the next expected %llu "
                "(at most %.0f, the longest gap in one-row blocks)",
                static_cast<unsigned long long>(sequence),
                static_cast<unsigned long long>(sequence - expected),
                static_cast<unsigned long long>(expected), max_ahead);
  return text;
}

NetSource::NetSource(Options options) : options_(std::move(options)) {
  listener_ = TcpSocket::listen_on(options_.host, options_.port);
  port_ = listener_.local_port();
  if (options_.expected) set_layout(*options_.expected);
}

NetSource::~NetSource() { stop(); }

int NetSource::max_block_rows() const { return static_cast<int>(stream_protocol::kMaxRows); }

int NetSource::max_channels() const {
  return options_.expected ? static_cast<int>(options_.expected->channels.size())
                           : static_cast<int>(stream_protocol::kMaxChannels);
}

std::string NetSource::describe() const {
  return "net " + options_.host + ":" + std::to_string(port_);
}

void NetSource::interrupt() { listener_.shutdown(); }

void NetSource::kind_counters(SourceCounters& counters) const {
  counters.network.connections = connections_.load(std::memory_order_relaxed);
  counters.network.malformed_frames = malformed_frames_.load(std::memory_order_relaxed);
  counters.network.layout_mismatches = layout_mismatches_.load(std::memory_order_relaxed);
}

void NetSource::run() {
  while (!stop_requested()) {
    TcpSocket peer = listener_.accept_for(kPollMs);
    if (!peer.valid()) continue;
    connections_.fetch_add(1, std::memory_order_relaxed);
    const std::string who = peer.peer();
    post_event({kNoTime, EventKind::Connected, "sender " + who});
    connected_.store(true, std::memory_order_release);
    const bool ended = serve(peer);
    connected_.store(false, std::memory_order_release);
    post_event({kNoTime, EventKind::Disconnected, "sender " + who});
    if (ended) return;
  }
}

// A HELLO: the sender's layout checked against the stream's (refused: false), a new stream's
// clock started after the last sample received.
bool NetSource::accept_hello(const stream_protocol::Hello& hello) {
  if (const std::optional<Sidecar> current = layout()) {
    const std::string difference = layout_difference(*current, hello.sidecar);
    if (!difference.empty()) {
      layout_mismatches_.fetch_add(1, std::memory_order_relaxed);
      post_event({kNoTime,
                  EventKind::LayoutMismatch,
                  "sender refused: " + difference,
                  {{"stream_id", hello.stream_id}}});
      return false;
    }
  } else {
    set_layout(hello.sidecar);
  }
  const double rate_hz = hello.sidecar.sample_rate_hz;
  if (hello.stream_id != stream_id_) {
    // A new stream: its clock starts after the last sample received.
    if (!stream_id_.empty()) {
      post_event({static_cast<double>(next_sample_) / rate_hz, EventKind::Discontinuity,
                  "a new stream \"" + hello.stream_id + "\" follows \"" + stream_id_ + "\""});
    }
    stream_id_ = hello.stream_id;
    sample_offset_ = static_cast<std::int64_t>(next_sample_);
    sequence_offset_ = static_cast<std::int64_t>(next_sequence_);
  }
  return true;
}

// A DATA frame: refused when it jumps too far ahead or its sequence is absurd, else its samples
// onto the queue on this receiver's clock.
void NetSource::accept_data(const stream_protocol::Frame& frame, double rate_hz) {
  // The sender's own numbering: the next sample it should send is where it left off.
  const std::uint64_t expected = next_sample_ - static_cast<std::uint64_t>(sample_offset_);
  const double ahead_s =
      (static_cast<double>(frame.first_sample) - static_cast<double>(expected)) / rate_hz;
  if (ahead_s * rate_hz > max_gap_samples(rate_hz)) {
    malformed_frames_.fetch_add(1, std::memory_order_relaxed);
    char text[200];
    std::snprintf(text, sizeof text,
                  "DATA frame refused: first_sample %llu is %.3g s past the next "
                  "expected sample %llu (at most %g s, %.0f samples)",
                  static_cast<unsigned long long>(frame.first_sample), ahead_s,
                  static_cast<unsigned long long>(expected), max_gap_samples(rate_hz) / rate_hz,
                  max_gap_samples(rate_hz));
    post_event({kNoTime, EventKind::MalformedFrame, text});
    return;
  }
  if (const std::string problem = sequence_problem(frame.sequence, rate_hz); !problem.empty()) {
    malformed_frames_.fetch_add(1, std::memory_order_relaxed);
    post_event({kNoTime, EventKind::MalformedFrame, problem});
    return;
  }
  const std::uint64_t first = frame.first_sample + static_cast<std::uint64_t>(sample_offset_);
  const std::uint64_t sequence = frame.sequence + static_cast<std::uint64_t>(sequence_offset_);
  next_sample_ = std::max(next_sample_, first + static_cast<std::uint64_t>(frame.rows));
  next_sequence_ = std::max(next_sequence_, sequence + 1);
  // A full queue holds the sender back through TCP for a while; a consumer still
  // behind after that loses the block (counted, and a gap downstream).
  RawBlock* block = begin_block_within(kBackpressure);
  if (block == nullptr) {
    count_overflow(first);
    return;
  }
  const std::size_t count =
      static_cast<std::size_t>(frame.rows) * static_cast<std::size_t>(frame.channels);
  for (std::size_t i = 0; i < count; ++i) {
    block->values[i] = stream_protocol::read_f64_le(frame.data + 8 * i);
  }
  block->sequence = sequence;
  block->first_sample = first;
  block->rows = frame.rows;
  block->channels = frame.channels;
  end_block(*block);
}

// An EVENT frame: refused when its fields are absurd, else posted on this receiver's clock.
void NetSource::accept_event(const stream_protocol::Frame& frame, double rate_hz) {
  StreamEvent event = *frame.event;
  if (const std::string problem = stream_event_problem(event, rate_hz); !problem.empty()) {
    malformed_frames_.fetch_add(1, std::memory_order_relaxed);
    post_event({kNoTime, EventKind::MalformedFrame, "EVENT frame refused: " + problem});
    return;
  }
  // The sender's stream times, moved onto this receiver's clock.
  const double shift_s = static_cast<double>(sample_offset_) / rate_hz;
  if (std::isfinite(event.t_s)) event.t_s += shift_s;
  for (const char* key : {"steady_from_s", "steady_to_s", "from_s", "to_s"}) {
    if (event.data.contains(key) && event.data[key].is_number()) {
      event.data[key] = event.data[key].get<double>() + shift_s;
    }
  }
  event.wall.clear();
  post_event(std::move(event));
}

bool NetSource::serve(TcpSocket& peer) {
  stream_protocol::FrameDecoder decoder;
  std::vector<std::uint8_t> buffer(1u << 16);
  bool greeted = false;
  double rate_hz = 0.0;
  for (;;) {
    if (stop_requested()) return false;
    const long got = peer.receive_for(buffer.data(), buffer.size(), kPollMs);
    if (got == -1) continue;
    if (got <= 0) return false;  // closed or failed: wait for the next sender
    decoder.feed(buffer.data(), static_cast<std::size_t>(got));
    stream_protocol::Frame frame;
    while (decoder.next(frame)) {
      using stream_protocol::FrameType;
      if (!frame.refused.empty()) {  // one frame left out, the stream goes on
        malformed_frames_.fetch_add(1, std::memory_order_relaxed);
        post_event({kNoTime, EventKind::MalformedFrame, frame.refused});
        continue;
      }
      if (!greeted && frame.type != FrameType::Hello) {
        malformed_frames_.fetch_add(1, std::memory_order_relaxed);
        post_event({kNoTime, EventKind::MalformedFrame, "the sender did not open with HELLO"});
        return false;
      }
      switch (frame.type) {
        case FrameType::Hello:
          if (!accept_hello(*frame.hello)) return false;
          rate_hz = frame.hello->sidecar.sample_rate_hz;
          greeted = true;
          break;
        case FrameType::Data:
          accept_data(frame, rate_hz);
          break;
        case FrameType::Event:
          accept_event(frame, rate_hz);
          break;
        case FrameType::Bye:
          post_event({static_cast<double>(next_sample_) / rate_hz, EventKind::SourceEnded,
                      "the sender ended its stream"});
          return true;
      }
    }
    if (!decoder.error().empty()) {
      malformed_frames_.fetch_add(1, std::memory_order_relaxed);
      post_event({kNoTime, EventKind::MalformedFrame, "connection closed: " + decoder.error()});
      return false;
    }
  }
}

}  // namespace oscilab::daq
