#pragma once

#include "analysis/simulation/table_motion.h"

namespace oscilab::analysis {

/// A slow sweep of the forcing amplitude at fixed frequency (§4.2, Fig. 12): f0 rises linearly
/// from 0 to `f0_max_n` over `up_s`, then falls linearly back to 0 over `down_s`.
///
/// Table motion b(t) = A(t) sin ωt with A = f0(t)/(m ω²), so that the force is
/// f = −m b̈ = f0(t) sin ωt − 2 (m ω A') cos ωt = f0(t) sin ωt − (2 f0'/ω) cos ωt   (A'' = 0).
/// The second term is the price of a table displacement that stays a clean sine; for a sweep of
/// 2 N in 400 s at ω ≈ 20 rad/s it is 5e-4 N, a hundred times less than the gap between the
/// folds of eq. (14). Only at the turning point (and t = 0) is b̈ discontinuous, by that much.
class AmplitudeSweepMotion final : public TableMotion {
 public:
  /// Throws InputError on a non-positive frequency, mass, amplitude or sweep time.
  AmplitudeSweepMotion(double freq_hz, double f0_max_n, double up_s, double down_s, double mass_kg);

  TableState at(double t_s) const override;
  double duration_s() const override { return up_s_ + down_s_; }
  /// f0(t), N: the amplitude of the sine part of the force.
  double f0_n(double t_s) const;
  /// df0/dt, N/s.
  double f0_rate_n_s(double t_s) const;
  double freq_hz() const { return freq_hz_; }
  double up_s() const { return up_s_; }

 private:
  double freq_hz_, f0_max_n_, up_s_, down_s_, mass_kg_;
};

}  // namespace oscilab::analysis
