#include "analysis/hbm/floquet.h"

#include <cmath>
#include <complex>
#include <numbers>

#include <gtest/gtest.h>
#include <Eigen/LU>

#include "analysis/model/polynomial_stiffness.h"
#include "analysis/model/reference_models.h"
#include "analysis/model/viscous_damping.h"

namespace oscilab::analysis {
namespace {

TEST(FloquetAnalysis, LinearOscillatorMultipliersMatchClosedForm) {
  // m z̈ + c ż + k z: Φ(T) = exp(A T), multipliers exp((−c/2m ± i ω_d) T).
  const double m = 0.5, k = 2000.0, c = 4.0, freq = 7.0;
  std::vector<std::unique_ptr<ModelTerm>> terms;
  terms.push_back(std::make_unique<PolynomialStiffness>(std::vector<double>{0.0, k}));
  terms.push_back(std::make_unique<ViscousDamping>(c));
  HarmonicBalance hbm(Model(m, std::move(terms)), freq, {});
  Eigen::VectorXd x = Eigen::VectorXd::Zero(hbm.size());
  ASSERT_TRUE(hbm.solve(x, 1.0).converged());
  const FloquetResult result = FloquetAnalysis().analyse(hbm, x);
  const double period = 1.0 / freq, decay = c / (2 * m);
  const double omega_d = std::sqrt(k / m - decay * decay);
  const std::complex<double> expected =
      std::exp(std::complex<double>(-decay * period, omega_d * period));
  // RK4 with h = T/1024 on a system with |λ| h ≈ 0.009: relative error ~ (λh)⁴/120·steps ≈ 1e-10.
  EXPECT_NEAR(std::abs(result.multipliers[0] - expected) / std::abs(expected), 0.0, 1e-8);
  EXPECT_NEAR(std::abs(result.multipliers[1] - std::conj(expected)) / std::abs(expected), 0.0,
              1e-8);
  EXPECT_TRUE(result.stable);
}

TEST(FloquetAnalysis, Rk4ConvergesAtFourthOrderAndSatisfiesLiouville) {
  // Eq. (14) at 0.8 N on the lower branch, where the friction switch is resolved: the error of
  // Φ(T) against a 16384-step reference falls by 2⁴ per halving of h.
  const Model model = illustrative_model();
  HarmonicBalance hbm(model, 0.8 * std::sqrt(800.0 / 1.3) / (2 * std::numbers::pi), {});
  Eigen::VectorXd x = hbm.linear_guess(0.0, 0.0);
  ASSERT_TRUE(hbm.solve(x, 0.8).converged());
  const Eigen::Matrix2d reference = FloquetAnalysis({16384}).analyse(hbm, x).monodromy;
  const double e256 = (FloquetAnalysis({256}).analyse(hbm, x).monodromy - reference).norm();
  const double e512 = (FloquetAnalysis({512}).analyse(hbm, x).monodromy - reference).norm();
  EXPECT_NEAR(e256 / e512, 16.0, 3.0);  // RK4: error ∝ h⁴ (measured 17.7)

  // Liouville: det Φ(T) = exp(∫ tr A dt) = exp(−∫ C/m dt); both sides from the same samples, so
  // they differ by the RK4 error only (≤ 1e-6 relative at the default 1024 steps). At 2 N, where
  // the mass no longer sticks, det Φ ≈ 0.19; while it sticks (0.8 N) det Φ ≈ 1e-35 is far below
  // the rounding of Φ's entries and cannot be checked this way.
  ASSERT_TRUE(hbm.solve(x, 2.0).converged());
  const FloquetResult result = FloquetAnalysis().analyse(hbm, x);
  EXPECT_GT(result.liouville_determinant, 0.1);
  EXPECT_NEAR(result.monodromy.determinant() / result.liouville_determinant, 1.0, 1e-6);
}

}  // namespace
}  // namespace oscilab::analysis
