#include "analysis/simulation/amplitude_sweep_motion.h"

#include <cmath>
#include <numbers>
#include <string>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {

AmplitudeSweepMotion::AmplitudeSweepMotion(double freq_hz, double f0_max_n, double up_s,
                                           double down_s, double mass_kg)
    : freq_hz_(freq_hz), f0_max_n_(f0_max_n), up_s_(up_s), down_s_(down_s), mass_kg_(mass_kg) {
  if (!(freq_hz > 0.0) || !(f0_max_n > 0.0) || !(up_s > 0.0) || !(down_s > 0.0) ||
      !(mass_kg > 0.0)) {
    throw InputError("amplitude sweep: frequency (" + std::to_string(freq_hz) + " Hz), f0_max (" +
                     std::to_string(f0_max_n) + " N), sweep times (" + std::to_string(up_s) + ", " +
                     std::to_string(down_s) + " s) and mass must be positive");
  }
}

double AmplitudeSweepMotion::f0_n(double t_s) const {
  if (t_s <= 0.0 || t_s >= duration_s()) return 0.0;
  if (t_s <= up_s_) return f0_max_n_ * t_s / up_s_;
  return f0_max_n_ * (1.0 - (t_s - up_s_) / down_s_);
}

double AmplitudeSweepMotion::f0_rate_n_s(double t_s) const {
  if (t_s <= 0.0 || t_s >= duration_s()) return 0.0;
  return t_s <= up_s_ ? f0_max_n_ / up_s_ : -f0_max_n_ / down_s_;
}

TableState AmplitudeSweepMotion::at(double t_s) const {
  const double omega = 2.0 * std::numbers::pi * freq_hz_;
  const double k = 1.0 / (mass_kg_ * omega * omega);  // A = f0 k
  const double a = f0_n(t_s) * k, a_dot = f0_rate_n_s(t_s) * k;
  const double s = std::sin(omega * t_s), c = std::cos(omega * t_s);
  return {a * s, a_dot * s + a * omega * c, -omega * omega * a * s + 2.0 * omega * a_dot * c};
}

}  // namespace oscilab::analysis
