#pragma once

#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "analysis/common/job.h"
#include "daq/network/tcp_socket.h"
#include "daq/sources/sample_source.h"

namespace oscilab::daq {

/// Sends a live source (the virtual rig, a replay) to a listening receiver in the Oscilab stream
/// protocol (docs/stream-protocol.md): the reference sender behind `oscilab-cli stream`.
///
/// One run is one stream: HELLO (a stream_id and the source's sidecar), then the source's blocks
/// as DATA frames in the order the source delivers them, with its `level`, `mark`,
/// `discontinuity` and `invalid` events as EVENT frames (other kinds are the sender's own
/// business), and BYE when the source ends or the run is cancelled. Every event reaches the
/// receiver before the block that reaches its time: a source posts an event before it publishes
/// that block, and the sender takes the events after it has looked at the next block.
///
/// Pacing is the source's: a rig or replay at 1× is sent in real time, at speed 0 as fast as
/// the receiver takes it (TCP's flow control then holds the source back, nothing is dropped).
///
/// The first connection is not retried: nobody listening is an error naming host:port
/// (Status::NoReceiver), and the source never starts. When the receiver goes away later, the
/// sender reconnects every 200 ms for up to `retry_s` with the same stream_id and goes on with
/// its sequence numbers and sample indices, so the receiver sees what was lost meanwhile as a
/// gap. The frame whose send failed is lost (a block is counted as lost); a live source that
/// finds its queue full meanwhile drops blocks itself (an overflow, and a gap in its sequence),
/// a replay as fast as possible waits. No connection within `retry_s` ends the run
/// (ReceiverGone).
///
/// Cancellation is noticed between frames and while a send waits for a receiver that does not
/// read: the source is stopped, and a BYE ends the stream when the connection can still take
/// it (a frame cut short leaves the connection closed without one).
///
/// Thread-safety: run() on one thread at a time; counters() and the CancelToken from any thread.
class StreamSender {
 public:
  struct Options {
    std::string host = "127.0.0.1";  // the receiver: IPv4 address, "localhost" or a host name
    std::uint16_t port = 0;          // required, 1..65535
    double retry_s = 10.0;  // after a break, try to reconnect this long; <= 0: give up at once
    std::string stream_id;  // empty: a random "oscilab-…" id for each run
    std::size_t queue_blocks = 256;      // between the source's thread and the sender
    std::uint64_t expected_samples = 0;  // the stream's length for progress; 0: not reported
  };
  enum class Status {
    Ok,            // the source ended and the stream was closed with BYE
    Cancelled,     // the CancelToken stopped it
    NoReceiver,    // the first connection failed
    ReceiverGone,  // no connection again within retry_s after a break
  };
  /// What a sender has done so far.
  struct Counters {
    std::uint64_t blocks_sent = 0;
    std::uint64_t blocks_lost = 0;  // whose send failed when the connection broke
    std::uint64_t reconnections = 0;
    bool connected = false;  // whether a connection is up now (counters() while running)
  };
  struct Result {
    Status status = Status::Ok;
    std::string message;    // why, for NoReceiver and ReceiverGone; names host:port
    std::string stream_id;  // the HELLO's
    Counters counters;
  };

  /// Throws InputError naming the option on invalid options.
  explicit StreamSender(Options options);

  /// Connects, starts `source` (which must know its layout, and not be started) and sends until
  /// it ends, the run is cancelled or the receiver is gone; the source is stopped on return.
  /// `progress` gets the fraction of expected_samples sent, after each block (on this thread).
  /// Throws InputError when the source has no layout or an event exceeds the protocol's limits.
  Result run(SampleSource& source, const ProgressFn& progress = {}, const CancelToken& cancel = {});

  /// A snapshot, from any thread.
  Counters counters() const;

 private:
  enum class Sent { Yes, LostReconnected, Cancelled, ReceiverGone };

  /// Sends one frame; on a break reconnects (the frame is then lost).
  Sent deliver(const std::vector<std::uint8_t>& frame, const CancelToken& cancel);
  /// Sends one frame on the current connection. Yes, ReceiverGone (the connection failed) or
  /// Cancelled (the receiver did not take it; the connection is closed if the frame was cut).
  Sent send_frame(const std::vector<std::uint8_t>& frame, const CancelToken& cancel);
  /// Connects again and greets, for up to retry_s.
  Sent reconnect(const CancelToken& cancel);
  std::string address() const;

  Options options_;
  TcpSocket socket_;
  std::vector<std::uint8_t> hello_frame_;
  std::atomic<std::uint64_t> blocks_sent_{0}, blocks_lost_{0}, reconnections_{0};
  std::atomic<bool> connected_{false};
};

}  // namespace oscilab::daq
