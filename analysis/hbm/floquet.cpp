#include "analysis/hbm/floquet.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/LU>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {

FloquetAnalysis::FloquetAnalysis(FloquetOptions options) : options_(options) {
  if (options_.steps_per_forcing_period < 8) {
    throw InputError("floquet: steps_per_forcing_period: " +
                     std::to_string(options_.steps_per_forcing_period) + " must be at least 8");
  }
}

FloquetResult FloquetAnalysis::analyse(HarmonicBalance& hbm, const Eigen::VectorXd& x) {
  const int steps = options_.steps_per_forcing_period * hbm.forcing_harmonic();
  // Samples at t_k = k h/2 over one base period: even k are step starts, odd k midpoints.
  hbm.sample(x, 2 * steps, z_, z_dot_);
  const Model& model = hbm.model();
  const double inverse_mass = 1.0 / model.mass_kg();
  const double period_s = 2.0 * std::numbers::pi / hbm.base_omega();
  const double h = period_s / steps;

  auto a_at = [&](int k) {
    const int i = k % (2 * steps);
    const TermPartials p = model.partials(z_[i], z_dot_[i], nullptr);
    Eigen::Matrix2d a;
    a << 0.0, 1.0, -p.d_dz * inverse_mass, -p.d_dz_dot * inverse_mass;
    return a;
  };

  FloquetResult result;
  Eigen::Matrix2d phi = Eigen::Matrix2d::Identity();
  Eigen::Matrix2d a_start = a_at(0);
  double damping_integral = 0.0;  // ∫ C/m dt
  for (int s = 0; s < steps; ++s) {
    const Eigen::Matrix2d a_mid = a_at(2 * s + 1), a_end = a_at(2 * s + 2);
    const Eigen::Matrix2d k1 = a_start * phi;
    const Eigen::Matrix2d k2 = a_mid * (phi + 0.5 * h * k1);
    const Eigen::Matrix2d k3 = a_mid * (phi + 0.5 * h * k2);
    const Eigen::Matrix2d k4 = a_end * (phi + h * k3);
    phi += (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    damping_integral -= 0.5 * h * (a_start(1, 1) + a_mid(1, 1));
    a_start = a_end;
  }
  result.monodromy = phi;
  result.liouville_determinant = std::exp(-damping_integral);

  // Eigenvalues of a real 2×2: μ = tr/2 ± √(tr²/4 − det).
  const double trace = phi.trace(), det = phi.determinant();
  const std::complex<double> root =
      std::sqrt(std::complex<double>(0.25 * trace * trace - det, 0.0));
  std::complex<double> mu1 = 0.5 * trace + root, mu2 = 0.5 * trace - root;
  if (std::abs(mu2) > std::abs(mu1)) std::swap(mu1, mu2);
  result.multipliers = {mu1, mu2};
  result.max_abs = std::abs(mu1);
  result.stable = result.max_abs < 1.0;
  result.fold_test = 1.0 - trace + det;
  result.flip_test = 1.0 + trace + det;
  return result;
}

}  // namespace oscilab::analysis
