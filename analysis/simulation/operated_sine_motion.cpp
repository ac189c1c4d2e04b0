#include "analysis/simulation/operated_sine_motion.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// ∫₀ˢ S(u) du of the quintic step S = 6u⁵ − 15u⁴ + 10u³; past the ramp S = 1.
double step_integral(double s) {
  if (s <= 0.0) return 0.0;
  if (s >= 1.0) return 0.5 + (s - 1.0);
  const double s2 = s * s;
  return s2 * s2 * (2.5 + s * (-3.0 + s));
}

}  // namespace

OperatedSineMotion::OperatedSineMotion(double mass_kg, double frequency_hz, double ramp_s)
    : mass_kg_(mass_kg), ramp_s_(ramp_s), initial_omega_(kTwoPi * frequency_hz) {
  if (!(mass_kg > 0) || !(ramp_s > 0) || !(frequency_hz > 0) || !std::isfinite(ramp_s) ||
      !std::isfinite(frequency_hz)) {
    throw InputError("operated sine: mass, ramp and frequency must be positive (got " +
                     std::to_string(mass_kg) + " kg, " + std::to_string(ramp_s) + " s, " +
                     std::to_string(frequency_hz) + " Hz)");
  }
}

double OperatedSineMotion::target_frequency_hz() const {
  return (changes_.empty() ? initial_omega_ : changes_.back().omega_to) / kTwoPi;
}

void OperatedSineMotion::change(double t_s, double f0_n, double frequency_hz) {
  if (!(f0_n >= 0) || !std::isfinite(f0_n)) {
    throw InputError("operated sine: amplitude " + std::to_string(f0_n) + " N must be >= 0");
  }
  if (!(frequency_hz > 0) || !std::isfinite(frequency_hz)) {
    throw InputError("operated sine: frequency " + std::to_string(frequency_hz) +
                     " Hz must be positive");
  }
  if (!changes_.empty() && t_s < changes_.back().t_s) {
    throw InputError("operated sine: a change at t = " + std::to_string(t_s) +
                     " s comes before the last one");
  }
  Change next;
  next.t_s = t_s;
  next.omega_to = kTwoPi * frequency_hz;
  next.f0_to_n = f0_n;
  if (changes_.empty()) {
    next.f0_from_n = 0.0;
    next.omega_from = initial_omega_;
    next.phase_rad = 0.0;
  } else {
    // Start from where the motion is at t_s, even inside an unfinished ramp.
    const Change& last = changes_.back();
    double phi = 0.0, omega = 0.0, omega_dot = 0.0;
    phase_at(last, t_s, phi, omega, omega_dot);
    const double s = (t_s - last.t_s) / ramp_s_;
    next.f0_from_n = last.f0_from_n + (last.f0_to_n - last.f0_from_n) * smooth_step(s).value;
    next.omega_from = omega;
    next.phase_rad = std::fmod(phi, kTwoPi);
  }
  changes_.push_back(next);
}

void OperatedSineMotion::phase_at(const Change& change, double t_s, double& phi, double& omega,
                                  double& omega_dot) const {
  const double s = (t_s - change.t_s) / ramp_s_;
  const SmoothStep step = smooth_step(s);
  const double d_omega = change.omega_to - change.omega_from;
  omega = change.omega_from + d_omega * step.value;
  omega_dot = d_omega * step.slope / ramp_s_;
  phi = change.phase_rad + change.omega_from * (t_s - change.t_s) +
        d_omega * ramp_s_ * step_integral(s);
}

TableState OperatedSineMotion::at(double t_s) const {
  // The segment of the last change at or before t (at rest before the first).
  const auto after = std::upper_bound(changes_.begin(), changes_.end(), t_s,
                                      [](double t, const Change& c) { return t < c.t_s; });
  if (after == changes_.begin()) return {};
  const Change& change = *(after - 1);

  double phi = 0.0, omega = 0.0, omega_dot = 0.0;
  phase_at(change, t_s, phi, omega, omega_dot);
  const double s = (t_s - change.t_s) / ramp_s_;
  const SmoothStep step = smooth_step(s);
  const double d_omega = change.omega_to - change.omega_from;
  const double omega_ddot = d_omega * step.curvature / (ramp_s_ * ramp_s_);
  const double d_f0 = change.f0_to_n - change.f0_from_n;
  const double f0 = change.f0_from_n + d_f0 * step.value;
  const double f0_dot = d_f0 * step.slope / ramp_s_;
  const double f0_ddot = d_f0 * step.curvature / (ramp_s_ * ramp_s_);

  // a = f0 g with g = 1/(m ω²): g' = −2ω'/(mω³), g'' = (6ω'²/ω⁴ − 2ω''/ω³)/m.
  const double g = 1.0 / (mass_kg_ * omega * omega);
  const double g_dot = -2.0 * omega_dot / (mass_kg_ * omega * omega * omega);
  const double g_ddot = (6.0 * omega_dot * omega_dot / (omega * omega * omega * omega) -
                         2.0 * omega_ddot / (omega * omega * omega)) /
                        mass_kg_;
  const double a = f0 * g;
  const double a_dot = f0_dot * g + f0 * g_dot;
  const double a_ddot = f0_ddot * g + 2.0 * f0_dot * g_dot + f0 * g_ddot;

  const double sin_phi = std::sin(phi), cos_phi = std::cos(phi);
  TableState state;
  state.b_m = a * sin_phi;
  state.b_dot_m_s = a_dot * sin_phi + a * omega * cos_phi;
  state.b_ddot_m_s2 = a_ddot * sin_phi + (2.0 * a_dot * omega + a * omega_dot) * cos_phi -
                      a * omega * omega * sin_phi;
  return state;
}

double OperatedSineMotion::duration_s() const { return std::numeric_limits<double>::infinity(); }

}  // namespace oscilab::analysis
