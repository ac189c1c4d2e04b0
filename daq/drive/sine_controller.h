#pragma once

#include <cstdint>
#include <string>

namespace oscilab::daq {

/// Where a sine drive is.
enum class DriveState : std::uint8_t {
  Idle,      // drive at zero, waiting for a level
  Ramping,   // the target amplitude or frequency is being ramped to a new level
  Settling,  // the ramp is over; the measured amplitude is not yet within the tolerance
  OnTarget,  // the last cycle's measured amplitude was within the tolerance of the target
  Stopping,  // ramping down to zero
  Aborted,   // a limit was crossed or an input lost: the drive is at zero until rearmed
};
const char* drive_state_name(DriveState state);

/// Why a drive aborted.
enum class DriveAbort : std::uint8_t {
  None,
  DriveLimit,              // the drive the level needs is above the amplifier's limit
  TableAccelerationLimit,  // a sample of |b̈| above its limit
  TravelLimit,             // the estimated relative displacement |z| above its limit
  InputLost,               // an input port lost its connection, gave a non-finite value or froze
};
const char* drive_abort_name(DriveAbort reason);

/// One change of the drive's state, as the event log keeps it.
struct DriveEvent {
  std::uint64_t sample = 0;  // the controller's sample count when it happened
  DriveState state = DriveState::Idle;
  DriveAbort abort = DriveAbort::None;
  double target_m_s2 = 0.0;    // the level's table-acceleration amplitude
  double frequency_hz = 0.0;   // the level's frequency
  double measured_m_s2 = 0.0;  // the last whole cycle's first-harmonic amplitude of b̈
  double drive_fs = 0.0;       // the drive amplitude, in the output's full-scale units
  int cycles = 0;              // OnTarget: whole cycles from the end of the ramp
  double value = 0.0;          // Aborted: the value that crossed its limit
};

/// Receives the controller's events on the thread that runs the controller (JACK's real-time
/// thread): it must not lock, allocate or block.
class DriveEventSink {
 public:
  virtual ~DriveEventSink() = default;
  virtual void drive_event(const DriveEvent& event) noexcept = 0;
};

struct SineControllerOptions {
  double sample_rate_hz = 48000.0;
  /// On target: |A₁ − A*| ≤ tolerance · A*, A₁ the first harmonic of b̈ over a whole cycle.
  double tolerance = 0.01;
  /// Ramp between levels (amplitude and frequency together); 0 steps.
  double ramp_s = 1.0;
  /// A first guess of the plant's gain: the table acceleration's amplitude per unit of drive
  /// amplitude (m/s² per full scale). The controller measures the gain from the first cycle on;
  /// a guess above the truth starts the ramp below its reference (the safe side).
  double gain_guess_m_s2_per_fs = 10.0;
  /// Abort limits.
  double max_drive_fs = 0.5;
  double max_table_acceleration_m_s2 = 50.0;
  double max_travel_m = 0.05;
  /// A drive that is on and sees an input with exactly the same value for this long: input lost.
  double frozen_input_s = 0.05;

  /// "" or what is wrong, naming the field.
  std::string validate() const;
};

/// An abort in words, without an interface's names: "the table acceleration reached 5.2 m/s²,
/// above the limit 5".
std::string drive_abort_text(const DriveEvent& event, const SineControllerOptions& limits);

/// A closed-loop sine controller (Oscilab's shaker drive). It plays the drive u = V sin φ and
/// brings the first harmonic of the measured table acceleration to the level's amplitude
/// A* = f0 / m: after each whole cycle of φ it measures A₁ = (2/N) |Σ b̈ₙ e^{iφₙ}| over that cycle
/// (the accelerometer's first harmonic at the drive's phase, insensitive to offsets, the
/// response's higher harmonics and noise averaged over the cycle's N samples) and the plant's gain
/// G = A₁ / V̄, V̄ the cycle's mean drive amplitude, and aims the next cycle at V = A_ref / G, the
/// reference A_ref where that cycle ends. V moves linearly over the cycle (no step in the drive).
/// A gain measurement is kept within ×2 of the last one per cycle, so one bad cycle cannot make
/// the drive jump.
///
/// Between levels the reference amplitude and the frequency follow the smooth step
/// S(s) = 3s² − 2s³ over `ramp_s`, with a continuous phase. A stop ramps to zero and ends Idle.
///
/// Abort limits are checked on every sample: a drive the level would need above `max_drive_fs`,
/// |b̈| above `max_table_acceleration_m_s2`, |z| above `max_travel_m` with
/// z = (y − y_rest) − b₁, y_rest the vibrometer's mean while idle and b₁ = −b̈₁ / ω² the table's
/// displacement from the last cycle's first harmonic b̈₁ of the acceleration; and an input lost (a
/// port disconnected, a non-finite value, or a value frozen for `frozen_input_s` while driving). An
/// abort sets the drive to zero from the sample it is found on, and holds it there until rearm().
///
/// Real-time safe: no allocation, lock or system call after construction. Not thread-safe: one
/// thread (JACK's process thread) calls everything.
class SineController {
 public:
  /// Throws InputError naming the field when the options are invalid.
  explicit SineController(const SineControllerOptions& options, DriveEventSink* sink = nullptr);

  /// A new level: ramp to amplitude A* (m/s²) at `frequency_hz`. From Idle the drive starts at
  /// phase 0, at that frequency. Returns false (and does nothing) when aborted, or when the
  /// values are not finite, the amplitude is negative, or the frequency is not within
  /// (0, rate/8].
  bool set_level(double amplitude_m_s2, double frequency_hz);
  /// Ramp down to zero (then Idle).
  void stop();
  /// Aborted → Idle (the operator's acknowledgement); nothing otherwise.
  void rearm();
  /// An input port has no connection: abort now, unless idle (nothing driven).
  void input_lost();

  /// One sample: the measured table acceleration (m/s²) and mass position (m) in, the drive out.
  double step(double table_acceleration_m_s2, double position_m);

  DriveState state() const { return state_; }
  DriveAbort abort_reason() const { return abort_; }
  double target_m_s2() const { return target_m_s2_; }
  double frequency_hz() const { return frequency_hz_; }
  double measured_m_s2() const { return measured_m_s2_; }
  double gain_m_s2_per_fs() const { return gain_; }
  double drive_fs() const { return drive_fs_; }
  /// Whole cycles from the end of the ramp to the first cycle within the tolerance (−1: not yet).
  int cycles_to_target() const { return cycles_to_target_; }
  std::uint64_t samples() const { return sample_; }

 private:
  void enter(DriveState state, int cycles = 0, double value = 0.0);
  void abort_with(DriveAbort reason, double value);
  void end_cycle();
  /// The ramp's reference amplitude `ahead` samples from now.
  double reference_at(std::uint64_t ahead) const;
  double ramp_fraction(std::uint64_t at) const;

  SineControllerOptions options_;
  DriveEventSink* sink_;
  double dt_s_;
  std::uint64_t frozen_limit_;

  DriveState state_ = DriveState::Idle;
  DriveAbort abort_ = DriveAbort::None;
  std::uint64_t sample_ = 0;

  // The level and its ramp.
  double target_m_s2_ = 0.0, frequency_hz_ = 0.0;
  double amplitude_from_m_s2_ = 0.0, omega_from_ = 0.0, omega_to_ = 0.0;
  std::uint64_t ramp_samples_ = 0, ramp_done_ = 0;
  bool stopping_ = false;

  // The drive.
  double phase_rad_ = 0.0, omega_rad_s_ = 0.0;
  double gain_;
  double drive_start_fs_ = 0.0, drive_goal_fs_ = 0.0, drive_fs_ = 0.0;

  // The cycle being measured and the last one.
  double sum_sin_ = 0.0, sum_cos_ = 0.0, sum_drive_ = 0.0;
  std::uint64_t cycle_samples_ = 0;
  double harmonic_sin_m_s2_ = 0.0, harmonic_cos_m_s2_ = 0.0, measured_m_s2_ = 0.0;
  bool have_harmonic_ = false;
  int cycles_since_ramp_ = 0, cycles_to_target_ = -1;

  // Inputs.
  double rest_position_m_ = 0.0;
  std::uint64_t rest_samples_ = 0;
  bool have_rest_ = false;
  double last_acceleration_ = 0.0;
  std::uint64_t frozen_samples_ = 0;
};

}  // namespace oscilab::daq
