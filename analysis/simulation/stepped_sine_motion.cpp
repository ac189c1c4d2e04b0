#include "analysis/simulation/stepped_sine_motion.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {

double SteppedSineSchedule::duration_s() const {
  return lead_in_s + hold_s * static_cast<double>(levels_n.size());
}

double SteppedSineSchedule::steady_start_s(std::size_t level) const {
  return lead_in_s + hold_s * static_cast<double>(level) + ramp_s;
}

double SteppedSineSchedule::steady_end_s(std::size_t level) const {
  return lead_in_s + hold_s * static_cast<double>(level + 1);
}

SmoothStep SteppedSineSchedule::amplitude_n(double t_s) const {
  if (levels_n.empty() || t_s < lead_in_s || t_s >= duration_s()) return {};
  const auto level = static_cast<std::size_t>((t_s - lead_in_s) / hold_s);
  const std::size_t i = std::min(level, levels_n.size() - 1);
  const double from = i == 0 ? 0.0 : levels_n[i - 1];
  const double to = levels_n[i];
  const double s = (t_s - lead_in_s - hold_s * static_cast<double>(i)) / ramp_s;
  const SmoothStep step = smooth_step(s);
  const double jump = to - from;
  return {from + jump * step.value, jump * step.slope / ramp_s,
          jump * step.curvature / (ramp_s * ramp_s)};
}

SteppedSineMotion::SteppedSineMotion(SteppedSineSchedule schedule, double mass_kg)
    : schedule_(std::move(schedule)), mass_kg_(mass_kg) {
  const SteppedSineSchedule& s = schedule_;
  if (!(s.frequency_hz > 0.0)) {
    throw InputError("stepped sine: frequency_hz: " + std::to_string(s.frequency_hz) +
                     " must be positive");
  }
  if (!(mass_kg > 0.0)) throw InputError("stepped sine: mass_kg must be positive");
  if (!(s.hold_s > 0.0) || !(s.ramp_s > 0.0) || s.ramp_s >= s.hold_s) {
    throw InputError("stepped sine: need 0 < ramp_s < hold_s (ramp " + std::to_string(s.ramp_s) +
                     " s, hold " + std::to_string(s.hold_s) + " s)");
  }
  if (!(s.lead_in_s >= 0.0)) throw InputError("stepped sine: lead_in_s must be >= 0");
  if (s.levels_n.empty()) throw InputError("stepped sine: levels: no level given");
  for (double f0 : s.levels_n) {
    if (!std::isfinite(f0) || f0 < 0.0) {
      throw InputError("stepped sine: levels: " + std::to_string(f0) +
                       " N is not a valid amplitude");
    }
  }
}

TableState SteppedSineMotion::at(double t_s) const {
  const double omega = 2.0 * std::numbers::pi * schedule_.frequency_hz;
  const double k = 1.0 / (mass_kg_ * omega * omega);  // A = f0 k
  const SmoothStep f0 = schedule_.amplitude_n(t_s);
  const double a = f0.value * k, a_dot = f0.slope * k, a_ddot = f0.curvature * k;
  const double s = std::sin(omega * t_s), c = std::cos(omega * t_s);
  return {a * s, a_dot * s + a * omega * c,
          (a_ddot - omega * omega * a) * s + 2.0 * omega * a_dot * c};
}

}  // namespace oscilab::analysis
