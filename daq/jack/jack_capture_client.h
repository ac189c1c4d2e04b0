#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "daq/jack/frame_slot_ring.h"
#include "daq/jack/jack_client.h"

struct _jack_client;  // libjack's jack_client_t (jack/types.h), kept out of this header
struct _jack_port;    // libjack's jack_port_t

namespace oscilab::daq {

/// A JACK client that captures some of a server's audio output ports: one input port per
/// channel (`in_<channel>`), each connected to its capture port. JACK's process callback only
/// copies the period's frames, interleaved, into a FrameSlotRing allocated before activation:
/// no lock, no allocation, no system call in the real-time thread. (While the server freewheels,
/// which is not real time, a full ring makes the callback wait for room instead of dropping.)
/// Each slot carries the server's frame time and which ports had no connection.
///
/// What the server says in its other callbacks (an xrun, a shutdown, a new rate, connections
/// changed, freewheeling) is kept in atomics for the reading thread to look at.
///
/// Thread-safety: open/activate/deactivate/close/connect_ports and the ring's consumer side from
/// one thread (the JACK source's); the flags from any thread.
class JackCaptureClient {
 public:
  struct Options {
    std::string server;  // empty: the default server
    std::string client_name;
    std::vector<std::string> capture_ports;  // one a channel, in order
    std::vector<std::string> channel_names;  // name the client's input ports
    double ring_s = 2.0;                     // server-rate frames the ring holds
  };

  explicit JackCaptureClient(Options options) : options_(std::move(options)) {}
  ~JackCaptureClient() { close(); }
  JackCaptureClient(const JackCaptureClient&) = delete;
  JackCaptureClient& operator=(const JackCaptureClient&) = delete;

  /// Opens the client (never starting a server), checks that every capture port exists and
  /// gives audio, registers the input ports, reads the server's rate and period and allocates
  /// the ring. Returns "" or why not (naming the server or the port), closed again then.
  std::string open();
  /// Sets the callbacks, activates the client and connects the ports. Returns "" or why not.
  std::string activate();
  /// The callback stops copying (the server unplugs the ports, which is no fault) and the
  /// client no longer runs.
  void deactivate();
  void close();
  /// Connects every input port to its capture port where it is not connected.
  void connect_ports();

  /// The audio output ports of a server (what can be captured). Throws InputError naming the
  /// server when none runs.
  static std::vector<std::string> capture_ports(const std::string& server);

  double rate_hz() const { return rate_hz_; }
  std::uint32_t period_frames() const { return period_; }
  FrameSlotRing& ring() { return ring_; }
  std::chrono::steady_clock::time_point last_connect_try() const { return last_connect_try_; }

  bool freewheeling() const { return freewheeling_.load(std::memory_order_acquire); }
  bool shut_down() const { return shutdown_.happened(); }
  /// When the server's shutdown was reported (meaningful when shut_down()).
  std::chrono::steady_clock::time_point shut_down_at() const { return shutdown_.at(); }
  /// Nonzero: the server switched to this rate.
  std::uint32_t changed_rate() const { return changed_rate_.load(std::memory_order_acquire); }
  /// Whether connections changed since the last call.
  bool take_connections_changed() { return connections_changed_.exchange(false); }
  /// Xruns the server reported since the client was made, and its frame clock at the last.
  std::uint64_t xruns() const { return xrun_count_.load(std::memory_order_acquire); }
  std::uint32_t last_xrun_frame() const { return xrun_frame_.load(std::memory_order_relaxed); }
  /// Frames the process callback had no room for in the ring, since the client was made.
  std::uint64_t dropped_frames() const { return dropped_.load(std::memory_order_relaxed); }

  // JACK's callbacks (through trampolines in the .cpp).
  int process(std::uint32_t frames);
  void on_shutdown() { shutdown_.report(); }
  void on_xrun();
  void on_rate(std::uint32_t rate);
  void on_connections_changed() { connections_changed_.store(true, std::memory_order_release); }
  void on_freewheel(bool starting) { freewheeling_.store(starting, std::memory_order_release); }

 private:
  Options options_;
  std::size_t channels() const { return options_.capture_ports.size(); }

  // --- shared with JACK's threads (callbacks) ---
  _jack_client* client_ = nullptr;
  std::vector<_jack_port*> ports_;
  std::vector<float*> buffers_;  // the process callback's port buffers (sized before activation)
  FrameSlotRing ring_;
  std::atomic<bool> freewheeling_{false}, connections_changed_{false};
  JackShutdown shutdown_;
  std::atomic<bool> closing_{false};  // the client is being deactivated: the callback never waits
  std::atomic<std::uint32_t> changed_rate_{0};
  std::atomic<std::uint64_t> xrun_count_{0};
  std::atomic<std::uint32_t> xrun_frame_{0};  // the server's frame clock at the last xrun
  std::atomic<std::uint64_t> dropped_{0};     // frames the ring had no room for

  double rate_hz_ = 0.0;
  std::uint32_t period_ = 0;
  std::chrono::steady_clock::time_point last_connect_try_;
};

}  // namespace oscilab::daq
