#pragma once

#include <atomic>
#include <optional>
#include <string>

#include "daq/network/tcp_socket.h"
#include "daq/sources/sample_source.h"

namespace oscilab::daq {

namespace stream_protocol {
struct Frame;
struct Hello;
}  // namespace stream_protocol

/// Receives the Oscilab stream protocol (stream_protocol.h, docs/stream-protocol.md) from one
/// sender at a time over TCP, listening on localhost unless told otherwise.
///
/// The first sender's HELLO fixes the layout (or the layout given to expect does); a later
/// sender whose channels or rate differ is refused (`layout-mismatch`, counted) and the receiver
/// waits for another. A sender that disconnects and comes back with the same stream_id continues
/// its sample clock (what it could not send shows as a gap); a new stream_id continues after the
/// last sample received, with a `discontinuity`. A malformed or hostile frame closes that
/// connection (`malformed-frame`, counted); the receiver never trusts a length it has not
/// checked (FrameDecoder) and keeps listening. A BYE ends the source. When the queue is full
/// the receiver stops reading for up to 2 s (TCP then slows the sender, nothing is lost); a
/// consumer still behind after that costs blocks, counted as overflow.
class NetSource final : public SampleSource {
 public:
  struct Options {
    std::string host = "127.0.0.1";
    std::uint16_t port = 0;           // 0: any free port (port() tells which)
    std::optional<Sidecar> expected;  // refuse senders whose layout differs from this
  };
  /// Binds the listening socket now (throws InputError naming the address when it cannot).
  explicit NetSource(Options options);
  ~NetSource() override;

  std::uint16_t port() const { return port_; }
  /// Whether a sender is connected now.
  bool connected() const { return connected_.load(std::memory_order_acquire); }

  int max_block_rows() const override;
  int max_channels() const override;
  std::string describe() const override;

 private:
  void run() override;
  void interrupt() override;
  void kind_counters(SourceCounters& counters) const override;
  /// Serves one sender; true when it ended the stream (BYE).
  bool serve(TcpSocket& peer);
  bool accept_hello(const stream_protocol::Hello& hello);
  void accept_data(const stream_protocol::Frame& frame, double rate_hz);
  void accept_event(const stream_protocol::Frame& frame, double rate_hz);
  /// Why a DATA frame's sequence (the sender's numbering) is refused, or "" when it is not.
  std::string sequence_problem(std::uint64_t sequence, double rate_hz) const;

  Options options_;
  TcpSocket listener_;
  std::uint16_t port_ = 0;
  std::atomic<bool> connected_{false};
  std::atomic<std::uint64_t> connections_{0}, malformed_frames_{0}, layout_mismatches_{0};
  // Stream clock across senders (touched by the source thread only).
  std::string stream_id_;
  std::uint64_t next_sample_ = 0, next_sequence_ = 0;  // one past the furthest seen
  std::int64_t sample_offset_ = 0, sequence_offset_ = 0;
};

/// Why two layouts differ, or "" when a stream of `offered` can be recorded as `expected`: same
/// rate, same channels (names, roles, quantities, units, calibration) in the same order.
std::string layout_difference(const Sidecar& expected, const Sidecar& offered);

}  // namespace oscilab::daq
