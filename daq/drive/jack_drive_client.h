#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <boost/lockfree/spsc_queue.hpp>

#include "daq/drive/sine_controller.h"
#include "daq/jack/frame_slot_ring.h"
#include "daq/jack/jack_client.h"

struct _jack_client;  // libjack's jack_client_t (jack/types.h), kept out of this header
struct _jack_port;    // libjack's jack_port_t

namespace oscilab::daq {

/// A drive event with the JACK frame it happened on.
struct TimedDriveEvent {
  DriveEvent event;
  std::uint32_t frame_time = 0;  // the server's frame clock (wraps at 2³²)
};

/// Oscilab's shaker drive on a JACK server: an output port `drive` (connected to the shaker
/// amplifier's playback port) and two input ports, `acceleration` and `position`, connected to
/// the accelerometer's and the vibrometer's capture ports (a recording's source may capture the
/// same ports beside it). The SineController runs in JACK's process callback, sample by sample,
/// so the drive reacts within the period it sees a sample in: an input port that loses its
/// connection aborts the drive before any of that period's drive is written.
///
/// Commands (a level, stop, rearm) reach the callback through a lock-free queue; the controller's
/// events come back through another, with the frame they happened on, for the event log; its
/// state is published in atomics after every period.
///
/// Thread-safety: start/stop/commands/take_events from one control thread; status from any.
class JackDriveClient {
 public:
  struct Options {
    std::string server;  // empty: the default server
    std::string client_name = "oscilab-drive";
    std::string drive_port;         // playback port the drive goes to; empty: none connected yet
    std::string acceleration_port;  // capture ports
    std::string position_port;
    double acceleration_scale_m_s2 = 1.0;  // SI per unit of the port (the sidecar's scale)
    double position_scale_m = 1.0;
    SineControllerOptions controller;  // its sample rate is the server's
    /// > 0: the inputs' frames (acceleration, position, as the ports give them) are also copied
    /// into a ring of this many seconds (capture()), each slot stamped with the controller's
    /// sample count at its first frame, for a level runner that records what it drove.
    double capture_s = 0.0;
  };

  struct Status {
    DriveState state = DriveState::Idle;
    DriveAbort abort = DriveAbort::None;
    double target_m_s2 = 0.0;
    double frequency_hz = 0.0;
    double measured_m_s2 = 0.0;
    double drive_fs = 0.0;
    int cycles_to_target = -1;
    std::uint64_t samples = 0;
  };

  explicit JackDriveClient(Options options) : options_(std::move(options)) {}
  ~JackDriveClient() { stop(); }
  JackDriveClient(const JackDriveClient&) = delete;
  JackDriveClient& operator=(const JackDriveClient&) = delete;

  /// Opens the client (never starting a server), checks the ports (capture ports that give
  /// audio, a playback port that takes it), registers its own, makes the controller at the
  /// server's rate, activates and connects. Returns "" or why not, naming the server, port or
  /// field.
  std::string start();
  /// Deactivates and closes the client: JACK unplugs the drive, the amplifier sees silence.
  void stop();

  /// Ramp to a new level (the table acceleration's amplitude A* = f0/m, and a frequency).
  /// Returns "" or why it was refused (a value out of range, the queue full).
  std::string set_level(double amplitude_m_s2, double frequency_hz);
  /// Ramp down to zero.
  std::string ramp_down();
  /// Aborted → idle.
  std::string rearm();

  Status status() const;
  /// The events since the last call, in order.
  std::vector<TimedDriveEvent> take_events();
  /// Events the callback had no room for (the control thread did not drain them).
  std::uint64_t lost_events() const { return lost_events_.load(std::memory_order_relaxed); }
  double rate_hz() const { return rate_hz_; }
  std::uint32_t period_frames() const { return period_; }
  bool shut_down() const { return shutdown_.happened(); }
  /// The captured frames (Options::capture_s), for one consumer thread: a slot's frame_time is
  /// the low 32 bits of the controller's sample count at its first frame (0-based).
  FrameSlotRing& capture() { return capture_; }
  /// Frames the capture ring had no room for, since the client started.
  std::uint64_t capture_dropped() const { return capture_dropped_.load(std::memory_order_relaxed); }
  /// "CLIENT:drive" etc. (the client's actual name).
  std::string port_name(const std::string& short_name) const;

  // JACK's callbacks (through trampolines in the .cpp).
  int process(std::uint32_t frames);
  void on_shutdown() { shutdown_.report(); }

 private:
  enum class CommandKind : std::uint8_t { Level, RampDown, Rearm };
  struct Command {
    CommandKind kind = CommandKind::Level;
    double amplitude_m_s2 = 0.0;
    double frequency_hz = 0.0;
  };
  /// Takes the controller's events in the real-time thread into the queue.
  class EventQueue final : public DriveEventSink {
   public:
    explicit EventQueue(JackDriveClient& owner) : owner_(owner) {}
    void drive_event(const DriveEvent& event) noexcept override;

   private:
    JackDriveClient& owner_;
  };
  std::string send(const Command& command);
  void copy_to_capture(const float* acceleration, const float* position, std::uint32_t frames);

  Options options_;
  _jack_client* client_ = nullptr;
  _jack_port* drive_out_ = nullptr;
  _jack_port* acceleration_in_ = nullptr;
  _jack_port* position_in_ = nullptr;
  double rate_hz_ = 0.0;
  std::uint32_t period_ = 0;

  // --- shared with JACK's process thread ---
  std::unique_ptr<SineController> controller_;
  EventQueue event_sink_{*this};
  std::uint32_t period_frame_time_ = 0, period_offset_ = 0;  // where the callback is
  boost::lockfree::spsc_queue<Command, boost::lockfree::capacity<64>> commands_;
  boost::lockfree::spsc_queue<TimedDriveEvent, boost::lockfree::capacity<1024>> events_;
  std::atomic<std::uint64_t> lost_events_{0};
  FrameSlotRing capture_;
  std::atomic<std::uint64_t> capture_dropped_{0};
  JackShutdown shutdown_;
  std::atomic<bool> closing_{false};
  std::atomic<int> state_{0}, abort_{0}, cycles_to_target_{-1};
  std::atomic<double> target_m_s2_{0.0}, frequency_hz_{0.0}, measured_m_s2_{0.0}, drive_fs_{0.0};
  std::atomic<std::uint64_t> samples_{0};
};

}  // namespace oscilab::daq
