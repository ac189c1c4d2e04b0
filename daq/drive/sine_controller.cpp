#include "daq/drive/sine_controller.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "analysis/common/input_error.h"

namespace oscilab::daq {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// How fast y_rest follows the vibrometer while idle (an exponential mean over about 0.2 s).
constexpr double kRestAveragingS = 0.2;
// A gain measurement moves the estimate by at most this factor per cycle.
constexpr double kMaxGainChange = 2.0;

bool usable_positive(double value) { return std::isfinite(value) && value > 0.0; }

}  // namespace

const char* drive_state_name(DriveState state) {
  switch (state) {
    case DriveState::Idle:
      return "idle";
    case DriveState::Ramping:
      return "ramping";
    case DriveState::Settling:
      return "settling";
    case DriveState::OnTarget:
      return "on_target";
    case DriveState::Stopping:
      return "stopping";
    case DriveState::Aborted:
      return "aborted";
  }
  return "unknown";
}

const char* drive_abort_name(DriveAbort reason) {
  switch (reason) {
    case DriveAbort::None:
      return "none";
    case DriveAbort::DriveLimit:
      return "drive_limit";
    case DriveAbort::TableAccelerationLimit:
      return "table_acceleration_limit";
    case DriveAbort::TravelLimit:
      return "travel_limit";
    case DriveAbort::InputLost:
      return "input_lost";
  }
  return "unknown";
}

std::string drive_abort_text(const DriveEvent& event, const SineControllerOptions& limits) {
  char text[200];
  switch (event.abort) {
    case DriveAbort::DriveLimit:
      std::snprintf(text, sizeof text,
                    "the level needs a drive of %.4g of full scale, above the limit %.4g",
                    event.value, limits.max_drive_fs);
      return text;
    case DriveAbort::TableAccelerationLimit:
      std::snprintf(text, sizeof text,
                    "the table acceleration reached %.4g m/s², above the limit %.4g", event.value,
                    limits.max_table_acceleration_m_s2);
      return text;
    case DriveAbort::TravelLimit:
      std::snprintf(text, sizeof text, "the mass moved %.4g m from rest, above the limit %.4g",
                    event.value, limits.max_travel_m);
      return text;
    case DriveAbort::InputLost:
      return "an input was lost (a port disconnected, a value not a number, or a frozen "
             "accelerometer)";
    case DriveAbort::None:
      break;
  }
  return "the drive aborted";
}

std::string SineControllerOptions::validate() const {
  if (!usable_positive(sample_rate_hz) || sample_rate_hz > 1e6) {
    return "sample rate: must be positive and at most 1 MHz";
  }
  if (!usable_positive(tolerance) || tolerance >= 0.5) return "tolerance: must be in (0, 0.5)";
  if (!std::isfinite(ramp_s) || ramp_s < 0.0 || ramp_s > 600.0) {
    return "ramp: must be 0 to 600 s";
  }
  if (!usable_positive(gain_guess_m_s2_per_fs) || gain_guess_m_s2_per_fs > 1e9) {
    return "drive gain guess: must be positive and finite";
  }
  if (!usable_positive(max_drive_fs) || max_drive_fs > 1.0) {
    return "drive limit: must be in (0, 1] of full scale";
  }
  if (!usable_positive(max_table_acceleration_m_s2)) {
    return "table acceleration limit: must be positive and finite";
  }
  if (!usable_positive(max_travel_m)) return "travel limit: must be positive and finite";
  if (!usable_positive(frozen_input_s) || frozen_input_s > 60.0) {
    return "frozen-input time: must be in (0, 60] s";
  }
  return "";
}

SineController::SineController(const SineControllerOptions& options, DriveEventSink* sink)
    : options_(options), sink_(sink) {
  if (const std::string why = options_.validate(); !why.empty()) {
    throw InputError("sine controller: " + why);
  }
  dt_s_ = 1.0 / options_.sample_rate_hz;
  frozen_limit_ = static_cast<std::uint64_t>(std::ceil(options_.frozen_input_s / dt_s_));
  gain_ = options_.gain_guess_m_s2_per_fs;
}

void SineController::enter(DriveState state, int cycles, double value) {
  state_ = state;
  if (sink_ == nullptr) return;
  DriveEvent event;
  event.sample = sample_;
  event.state = state;
  event.abort = abort_;
  event.target_m_s2 = target_m_s2_;
  event.frequency_hz = frequency_hz_;
  event.measured_m_s2 = measured_m_s2_;
  event.drive_fs = drive_fs_;
  event.cycles = cycles;
  event.value = value;
  sink_->drive_event(event);
}

void SineController::abort_with(DriveAbort reason, double value) {
  if (state_ == DriveState::Aborted) return;
  abort_ = reason;
  drive_fs_ = drive_start_fs_ = drive_goal_fs_ = 0.0;
  enter(DriveState::Aborted, 0, value);
}

bool SineController::set_level(double amplitude_m_s2, double frequency_hz) {
  if (state_ == DriveState::Aborted) return false;
  if (!std::isfinite(amplitude_m_s2) || amplitude_m_s2 < 0.0 || !usable_positive(frequency_hz) ||
      frequency_hz > options_.sample_rate_hz / 8.0) {
    return false;
  }
  const double omega = kTwoPi * frequency_hz;
  if (state_ == DriveState::Idle) {
    phase_rad_ = 0.0;
    omega_rad_s_ = omega;
    amplitude_from_m_s2_ = 0.0;
    drive_start_fs_ = drive_goal_fs_ = drive_fs_ = 0.0;
    sum_sin_ = sum_cos_ = sum_drive_ = 0.0;
    cycle_samples_ = 0;
    have_harmonic_ = false;
    measured_m_s2_ = 0.0;
  } else {
    amplitude_from_m_s2_ = reference_at(0);
  }
  omega_from_ = omega_rad_s_;
  omega_to_ = omega;
  target_m_s2_ = amplitude_m_s2;
  frequency_hz_ = frequency_hz;
  ramp_samples_ = static_cast<std::uint64_t>(std::llround(options_.ramp_s / dt_s_));
  ramp_done_ = 0;
  stopping_ = false;
  cycles_since_ramp_ = 0;
  cycles_to_target_ = -1;
  // The first cycle from rest aims at the reference where it ends.
  if (state_ == DriveState::Idle) {
    const double cycle_samples = options_.sample_rate_hz / frequency_hz;
    drive_goal_fs_ = reference_at(static_cast<std::uint64_t>(cycle_samples)) / gain_;
    if (drive_goal_fs_ > options_.max_drive_fs) {
      abort_with(DriveAbort::DriveLimit, drive_goal_fs_);
      return true;
    }
  }
  enter(ramp_samples_ > 0 ? DriveState::Ramping : DriveState::Settling);
  return true;
}

void SineController::stop() {
  if (state_ == DriveState::Idle || state_ == DriveState::Aborted) return;
  amplitude_from_m_s2_ = reference_at(0);
  omega_from_ = omega_to_ = omega_rad_s_;
  target_m_s2_ = 0.0;
  ramp_samples_ = static_cast<std::uint64_t>(std::llround(options_.ramp_s / dt_s_));
  ramp_done_ = 0;
  stopping_ = true;
  enter(DriveState::Stopping);
}

void SineController::rearm() {
  if (state_ != DriveState::Aborted) return;
  abort_ = DriveAbort::None;
  target_m_s2_ = 0.0;
  have_rest_ = false;
  frozen_samples_ = 0;
  enter(DriveState::Idle);
}

void SineController::input_lost() {
  // Idle, nothing is driven: an input without a connection yet (a client whose ports are being
  // connected) stops nothing. A level started without it aborts on its first sample.
  if (state_ == DriveState::Idle) return;
  abort_with(DriveAbort::InputLost, 0.0);
}

double SineController::ramp_fraction(std::uint64_t at) const {
  if (ramp_samples_ == 0 || at >= ramp_samples_) return 1.0;
  const double s = static_cast<double>(at) / static_cast<double>(ramp_samples_);
  return s * s * (3.0 - 2.0 * s);
}

double SineController::reference_at(std::uint64_t ahead) const {
  const double step = ramp_fraction(ramp_done_ + ahead);
  return amplitude_from_m_s2_ + (target_m_s2_ - amplitude_from_m_s2_) * step;
}

double SineController::step(double table_acceleration_m_s2, double position_m) {
  ++sample_;
  if (state_ == DriveState::Aborted) return 0.0;
  if (!std::isfinite(table_acceleration_m_s2) || !std::isfinite(position_m)) {
    abort_with(DriveAbort::InputLost, 0.0);
    return 0.0;
  }
  if (state_ == DriveState::Idle || !have_rest_) {
    // The mass's rest position, for the travel limit (the first sample's when the drive
    // started before any idle sample).
    // The mean of the samples so far, then an exponential mean over kRestAveragingS.
    rest_samples_ = have_rest_ ? rest_samples_ + 1 : 1;
    const double weight =
        std::max(1.0 / static_cast<double>(rest_samples_), dt_s_ / kRestAveragingS);
    rest_position_m_ += weight * (position_m - rest_position_m_);
    have_rest_ = true;
  }
  if (state_ == DriveState::Idle) {
    last_acceleration_ = table_acceleration_m_s2;
    return 0.0;
  }

  // Abort limits, on this sample.
  if (std::abs(table_acceleration_m_s2) > options_.max_table_acceleration_m_s2) {
    abort_with(DriveAbort::TableAccelerationLimit, std::abs(table_acceleration_m_s2));
    return 0.0;
  }
  frozen_samples_ = table_acceleration_m_s2 == last_acceleration_ ? frozen_samples_ + 1 : 0;
  last_acceleration_ = table_acceleration_m_s2;
  if (frozen_samples_ >= frozen_limit_ && drive_fs_ > 0.0) {
    abort_with(DriveAbort::InputLost, table_acceleration_m_s2);
    return 0.0;
  }
  const double sin_phase = std::sin(phase_rad_), cos_phase = std::cos(phase_rad_);
  if (have_harmonic_) {
    // b₁ = −b̈₁ / ω²: the table's displacement in the last cycle's first harmonic.
    const double table_m = -(harmonic_sin_m_s2_ * sin_phase + harmonic_cos_m_s2_ * cos_phase) /
                           (omega_rad_s_ * omega_rad_s_);
    const double travel_m = std::abs(position_m - rest_position_m_ - table_m);
    if (travel_m > options_.max_travel_m) {
      abort_with(DriveAbort::TravelLimit, travel_m);
      return 0.0;
    }
  }

  // The drive: its amplitude moves linearly over the cycle from its start to its goal.
  drive_fs_ = drive_start_fs_ + (drive_goal_fs_ - drive_start_fs_) * (phase_rad_ / kTwoPi);
  const double drive = drive_fs_ * sin_phase;
  sum_sin_ += table_acceleration_m_s2 * sin_phase;
  sum_cos_ += table_acceleration_m_s2 * cos_phase;
  sum_drive_ += drive_fs_;
  ++cycle_samples_;

  // Advance the ramp and the phase.
  if (ramp_done_ < ramp_samples_) {
    ++ramp_done_;
    omega_rad_s_ = omega_from_ + (omega_to_ - omega_from_) * ramp_fraction(ramp_done_);
    if (ramp_done_ == ramp_samples_ && !stopping_) enter(DriveState::Settling);
  }
  phase_rad_ += omega_rad_s_ * dt_s_;
  if (phase_rad_ >= kTwoPi) {
    phase_rad_ -= kTwoPi;
    end_cycle();
  }
  return drive;
}

void SineController::end_cycle() {
  const double n = static_cast<double>(cycle_samples_);
  harmonic_sin_m_s2_ = 2.0 * sum_sin_ / n;
  harmonic_cos_m_s2_ = 2.0 * sum_cos_ / n;
  measured_m_s2_ = std::hypot(harmonic_sin_m_s2_, harmonic_cos_m_s2_);
  have_harmonic_ = true;
  const double mean_drive_fs = sum_drive_ / n;
  sum_sin_ = sum_cos_ = sum_drive_ = 0.0;
  cycle_samples_ = 0;
  // Too little drive to measure the gain by (the first cycle from rest): keep the estimate.
  if (mean_drive_fs > 1e-6 * options_.max_drive_fs && measured_m_s2_ > 0.0) {
    const double measured_gain = measured_m_s2_ / mean_drive_fs;
    gain_ = std::clamp(measured_gain, gain_ / kMaxGainChange, gain_ * kMaxGainChange);
  }

  const bool ramp_over = ramp_done_ >= ramp_samples_;
  if (stopping_ && ramp_over && drive_goal_fs_ == 0.0) {
    drive_start_fs_ = drive_fs_ = 0.0;
    enter(DriveState::Idle);
    have_rest_ = false;
    return;
  }
  if (ramp_over && !stopping_) {
    ++cycles_since_ramp_;
    const bool within =
        std::abs(measured_m_s2_ - target_m_s2_) <= options_.tolerance * target_m_s2_;
    if (within && state_ != DriveState::OnTarget) {
      if (cycles_to_target_ < 0) cycles_to_target_ = cycles_since_ramp_;
      enter(DriveState::OnTarget, cycles_since_ramp_);
    } else if (!within && state_ == DriveState::OnTarget) {
      enter(DriveState::Settling, cycles_since_ramp_);
    }
  }

  // The next cycle aims at the reference where it ends.
  drive_start_fs_ = drive_goal_fs_;
  const auto next_cycle_samples =
      static_cast<std::uint64_t>(options_.sample_rate_hz * kTwoPi / omega_rad_s_);
  drive_goal_fs_ = reference_at(next_cycle_samples) / gain_;
  if (stopping_ && ramp_over) drive_goal_fs_ = 0.0;
  if (drive_goal_fs_ > options_.max_drive_fs) {
    abort_with(DriveAbort::DriveLimit, drive_goal_fs_);
  }
}

}  // namespace oscilab::daq
