#include "analysis/hbm/harmonic_balance.h"

#include <cmath>
#include <complex>
#include <numbers>

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"
#include "analysis/model/polynomial_stiffness.h"
#include "analysis/model/reference_models.h"
#include "analysis/model/viscous_damping.h"

namespace oscilab::analysis {
namespace {

// A response with every harmonic present, around the positive well of the paper's model.
Eigen::VectorXd rich_point(const HarmonicBalance& hbm, double z_star) {
  Eigen::VectorXd x(hbm.size());
  for (int i = 0; i < hbm.size(); ++i) x[i] = 2e-3 * std::sin(1.7 * i + 0.3) / (1 + i / 2);
  x[0] = z_star;
  return x;
}

// hbm --samples -1 used to mean the default silently; a negative N or one past the limit is
// refused.
TEST(HarmonicBalance, RefusesANegativeOrHugeSampleCount) {
  HbmOptions options;
  options.samples = -1;
  EXPECT_THROW(HarmonicBalance(paper_model(), 9.0, options), InputError);
  options.samples = (1 << 20) + 1;
  EXPECT_THROW(HarmonicBalance(paper_model(), 9.0, options), InputError);
  options.samples = 0;  // the default N
  EXPECT_NO_THROW(HarmonicBalance(paper_model(), 9.0, options));
}

TEST(HarmonicBalance, AnalyticJacobianMatchesCentralDifferences) {
  for (int nu : {1, 2}) {
    const Model model = paper_model();
    HbmOptions options;
    options.harmonics = 5;
    options.subharmonic = nu;
    HarmonicBalance hbm(model, 9.0, options);
    const Eigen::VectorXd x = rich_point(hbm, model.well(true).z_m);
    Eigen::VectorXd r, r_plus, r_minus;
    Eigen::MatrixXd jacobian;
    hbm.residual_and_jacobian(x, 1.3, r, jacobian);
    // Central differences with h = 1e-8 m: truncation ~h² R''' ≈ 1e-16·1e6 N, rounding
    // ~1e-16·1 N / 1e-8 m = 1e-8 N/m, against entries of order 1e2–1e3 N/m.
    const double h = 1e-8;
    double worst = 0.0;
    for (int j = 0; j < hbm.size(); ++j) {
      Eigen::VectorXd xp = x, xm = x;
      xp[j] += h;
      xm[j] -= h;
      hbm.residual(xp, 1.3, r_plus);
      hbm.residual(xm, 1.3, r_minus);
      const Eigen::VectorXd column = (r_plus - r_minus) / (2 * h);
      worst = std::max(worst, (column - jacobian.col(j)).cwiseAbs().maxCoeff());
    }
    EXPECT_LT(worst / jacobian.cwiseAbs().maxCoeff(), 1e-6) << "nu = " << nu;

    // ∂r/∂ω against a central difference in frequency (step 1e-5 Hz of 9 Hz).
    Eigen::VectorXd analytic;
    hbm.d_residual_d_omega(x, analytic);
    const double df = 1e-5;
    hbm.set_frequency(9.0 + df);
    hbm.residual(x, 1.3, r_plus);
    hbm.set_frequency(9.0 - df);
    hbm.residual(x, 1.3, r_minus);
    hbm.set_frequency(9.0);
    const Eigen::VectorXd numeric = (r_plus - r_minus) / (2 * df * 2 * std::numbers::pi);
    EXPECT_LT((numeric - analytic).norm() / analytic.norm(), 1e-6);
  }
}

TEST(HarmonicBalance, LinearOscillatorMatchesClosedForm) {
  const double m = 0.5, k = 2000.0, c = 4.0, f0 = 1.5, freq = 7.0;
  HarmonicBalance hbm(linear_oscillator_model(m, k, c), freq, {});
  Eigen::VectorXd x = Eigen::VectorXd::Zero(hbm.size());
  const NewtonReport report = hbm.solve(x, f0);
  ASSERT_TRUE(report.converged()) << report.message;
  const double w = 2 * std::numbers::pi * freq;
  // z = f0/|k − mω² + icω| sin(ωt − θ), θ = atan2(cω, k − mω²).
  const double amplitude = f0 / std::hypot(k - m * w * w, c * w);
  const double lag = std::atan2(c * w, k - m * w * w);
  const HbmMeasures measures = hbm.measure(x, f0);
  // Newton converges to ‖r‖ ≤ 1e-11 N; a linear system then has relative error ~1e-11 / f0.
  EXPECT_NEAR(std::abs(measures.z1_m) / amplitude, 1.0, 1e-10);
  // docs/conventions.md: θ1 = −π/2 − arg Z1.
  EXPECT_NEAR(-std::numbers::pi / 2 - std::arg(measures.z1_m), lag, 1e-10);
  EXPECT_NEAR(measures.edc_j / (std::numbers::pi * c * w * amplitude * amplitude), 1.0, 1e-10);
  // amp_m comes from sampled extremes refined by parabolas: O(Δτ⁴) ≈ 1e-9 at 256 samples.
  EXPECT_NEAR(measures.amp_m / amplitude, 1.0, 1e-8);
  EXPECT_LT(x.tail(hbm.size() - 3).norm(), 1e-14);  // no higher harmonics in a linear response
}

TEST(HarmonicBalance, EnergyIdentityHoldsOnConvergedPaperPoints) {
  // Eq. (13) (from Z1 alone) and ∮ D dz (from the time samples) agree on a converged point: the
  // discrete sums are exact for the trigonometric polynomials involved when N > 4νH (see
  // docs/hbm.md), so only the Newton residual (≤ 1e-11 N) separates them.
  const Model model = paper_model();
  for (bool positive : {true, false}) {
    for (int harmonics : {3, 7, 15}) {
      HbmOptions options;
      options.harmonics = harmonics;
      HarmonicBalance hbm(model, 9.0, options);
      const double z_star = model.well(positive).z_m;
      Eigen::VectorXd x = hbm.linear_guess(z_star, 0.0);
      for (double f0 : {0.2, 0.6, 1.0, 1.4, 1.8, 2.2, 2.7}) {
        const NewtonReport report = hbm.solve(x, f0);
        ASSERT_TRUE(report.converged()) << report.message << " at " << f0 << " N";
        const HbmMeasures measures = hbm.measure(x, f0);
        EXPECT_GT(measures.edc_j, 0.0);
        EXPECT_NEAR(measures.edc_dissipation_j / measures.edc_j, 1.0, 1e-6)
            << "H = " << harmonics << ", f0 = " << f0 << ", well " << positive;
      }
    }
  }
}

TEST(HarmonicBalance, ThrowsInputErrorOnBadOptions) {
  HbmOptions options;
  options.harmonics = 0;
  EXPECT_THROW(HarmonicBalance(paper_model(), 9.0, options), InputError);
  options.harmonics = 7;
  options.samples = 14;  // ≤ 2H
  EXPECT_THROW(HarmonicBalance(paper_model(), 9.0, options), InputError);
  EXPECT_THROW(HarmonicBalance(paper_model(), -1.0, {}), InputError);
}

}  // namespace
}  // namespace oscilab::analysis
