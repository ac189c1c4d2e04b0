#pragma once

#include <vector>

#include "analysis/simulation/table_motion.h"

namespace oscilab::analysis {

/// The table motion of a sine test run by an operator: force amplitude f0 and frequency ν are set
/// while the test runs, each change ramped smoothly so that b̈ stays continuous (no shock to the
/// rig, nothing for the integrator to resolve). The stepped sine of §3.2 is one such run.
///
/// Between changes the force on the mass is exactly f = −m b̈ = f0 sin φ(t), φ' = 2πν (eq. (11)).
/// A change at t_c ramps f0 and ω = 2πν together with the C² quintic step S(s),
/// s = (t − t_c)/ramp_s (table_motion.h), and keeps the phase continuous:
///   ω(t) = ω₀ + (ω₁ − ω₀) S(s),   φ(t) = φ(t_c) + ω₀ (t − t_c) + (ω₁ − ω₀) ramp_s I(s),
///   I(s) = ∫₀ˢ S = s⁶ − 3s⁵ + 5s⁴/2 (s ≤ 1), 1/2 + (s − 1) after.
/// The displacement is b = a(t) sin φ with a = f0 / (m ω²), so that
///   b̈ = a'' sin φ + (2a'ω + aω') cos φ − aω² sin φ.
///
/// Changes are appended in time order (each at or after the previous) by the one thread that
/// also integrates; not thread-safe.
class OperatedSineMotion final : public TableMotion {
 public:
  /// At rest until the first change; throws InputError on a non-positive mass, ramp or frequency.
  OperatedSineMotion(double mass_kg, double frequency_hz, double ramp_s);

  /// From t_s on, ramp to amplitude f0_n at frequency_hz over ramp_s. Throws InputError when
  /// t_s is before the last change, f0_n is negative or the frequency not positive.
  void change(double t_s, double f0_n, double frequency_hz);

  TableState at(double t_s) const override;
  /// Unbounded: the test runs until stopped.
  double duration_s() const override;

  double ramp_s() const { return ramp_s_; }
  /// The amplitude and frequency set last (where the ramp ends).
  double target_f0_n() const { return changes_.empty() ? 0.0 : changes_.back().f0_to_n; }
  double target_frequency_hz() const;

 private:
  struct Change {
    double t_s;
    double f0_from_n, f0_to_n;
    double omega_from, omega_to;  // rad/s
    double phase_rad;             // φ(t_s)
  };
  /// φ, ω, ω' at time t_s within `change`'s segment.
  void phase_at(const Change& change, double t_s, double& phi, double& omega,
                double& omega_dot) const;

  double mass_kg_;
  double ramp_s_;
  double initial_omega_;
  std::vector<Change> changes_;
};

}  // namespace oscilab::analysis
