#pragma once

#include <array>
#include <complex>

#include <Eigen/Core>

#include "analysis/hbm/harmonic_balance.h"

namespace oscilab::analysis {

/// Stability of a harmonic-balance periodic orbit from its Floquet multipliers, the eigenvalues
/// of the monodromy matrix Φ(T_b) of the variational equation over one response period
/// T_b = 2π/Ω = νT:
///
///   d/dt [δz; δż] = A(t) [δz; δż],   A(t) = [ 0, 1; −K(t)/m, −C(t)/m ],   Φ(0) = I,
///
/// with K = ∂R/∂z and C = ∂R/∂ż along the orbit. Integrated by classical fixed-step RK4 on an
/// orbit sampled at the half steps by an inverse FFT of the HBM coefficients.
///
/// Accuracy: RK4's global error is O(h⁴); the stiffest coefficient is C/m at the friction switch
/// (∂D/∂ż ≈ 4 f_d/v_t: ≈ 700 s⁻¹ for the paper's model, ≈ 335 s⁻¹ for eq. (14)), and the
/// default 512 steps per forcing period keep h·C/m ≤ 0.16 (paper, 9 Hz) and resolve the switch,
/// which lasts ≈ v_t/|z̈| (a few ms), with ≥ 5 steps. The tests check the h⁴ convergence and
/// Liouville's formula det Φ(T_b) = exp(−∫ C/m dt) (docs/hbm.md).
///
/// Markers: a real multiplier crosses +1 where det(Φ − I) changes sign (a fold of the branch), and
/// −1 where det(Φ + I) changes sign (period doubling).
struct FloquetOptions {
  int steps_per_forcing_period = 1024;
};

struct FloquetResult {
  Eigen::Matrix2d monodromy = Eigen::Matrix2d::Identity();
  std::array<std::complex<double>, 2> multipliers{};  // |μ1| ≥ |μ2|
  double max_abs = 0.0;
  bool stable = false;     // max |μ| < 1
  double fold_test = 0.0;  // det(Φ − I) = (1 − μ1)(1 − μ2)
  double flip_test = 0.0;  // det(Φ + I) = (1 + μ1)(1 + μ2)
  /// exp(−∫ C/m dt) over the period by the rectangle rule on the RK4 grid: det Φ should equal
  /// it (Liouville), an accuracy check.
  double liouville_determinant = 0.0;
};

/// Thread-safety: like HarmonicBalance, one object per thread.
class FloquetAnalysis {
 public:
  explicit FloquetAnalysis(FloquetOptions options = {});
  FloquetResult analyse(HarmonicBalance& hbm, const Eigen::VectorXd& x);

 private:
  FloquetOptions options_;
  Eigen::VectorXd z_, z_dot_;
};

}  // namespace oscilab::analysis
