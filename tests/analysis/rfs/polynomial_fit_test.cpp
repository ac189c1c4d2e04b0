// The polynomial least squares of the stiffness slice (eq. (2)) against an exact cubic, against
// the QR of the design matrix (a second method) on noisy samples, and its error paths.
#include "analysis/rfs/polynomial_fit.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {
namespace {

// A cubic of the paper's kind, K(z) = k3 z³ − k1 z + k0 (Table 1: k3 = 7.35e5 N/m³,
// k1 = 550 N/m), on positions of one well (z from 0.01 to 0.05 m, off-centre on purpose).
TEST(PolynomialFit, RecoversAnExactCubic) {
  const int n = 400;
  Eigen::VectorXd z(n), force(n);
  for (int i = 0; i < n; ++i) {
    z[i] = 0.01 + 0.04 * i / (n - 1.0);
    force[i] = 7.35e5 * std::pow(z[i], 3) + 2.0e3 * z[i] * z[i] - 550.0 * z[i] + 0.25;
  }
  const PolynomialFit fit = fit_polynomial(z, force, 3);
  ASSERT_EQ(fit.coefficients.size(), 4);
  // Rounding only: the coefficients in the plain powers of z carry the conversion from the
  // scaled variable (factors of 1/s³ ≈ 10⁵), so 1e-8 relative is the honest bound here.
  EXPECT_NEAR(fit.coefficients[3] / 7.35e5, 1.0, 1e-8);
  EXPECT_NEAR(fit.coefficients[2] / 2.0e3, 1.0, 1e-8);
  EXPECT_NEAR(fit.coefficients[1] / -550.0, 1.0, 1e-8);
  EXPECT_NEAR(fit.coefficients[0], 0.25, 1e-9);
  EXPECT_LT(fit.residual_rms, 1e-10);
  EXPECT_EQ(fit.samples, n);
}

// Noisy samples on u ∈ [−1, 1] (where the internal scaling is the identity): the coefficients,
// the residual rms and the standard errors σ² (AᵀA)⁻¹ equal those of the column-pivoting QR of
// the design matrix, computed here, to 1e-10 relative (the power sums' rounding is about 1e-13
// relative, polynomial_fit.cpp).
TEST(PolynomialFit, EqualsTheQrOfTheDesignOnNoisySamples) {
  std::mt19937 generator(17);
  std::uniform_real_distribution<double> position(-1.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.3);
  const int n = 5000, p = 4;
  Eigen::VectorXd u(n), y(n);
  for (int i = 0; i < n; ++i) {
    u[i] = position(generator);
    y[i] = 2.0 * std::pow(u[i], 3) - 1.5 * u[i] + 0.1 + noise(generator);
  }
  // Centre and scale exactly 0 and 1, so the fit's internal u is this u.
  u[0] = -1.0;
  u[1] = 1.0;
  u.array() -= u.mean();
  u /= u.cwiseAbs().maxCoeff();
  const PolynomialFit fit = fit_polynomial(u, y, 3);

  Eigen::MatrixXd design(n, p);
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < p; ++k) design(i, k) = std::pow(u[i], k);
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(design);
  const Eigen::VectorXd a = qr.solve(y);
  const Eigen::VectorXd residual = design * a - y;
  const double variance = residual.squaredNorm() / (n - p);
  const Eigen::MatrixXd covariance = variance * (design.transpose() * design).inverse();
  for (int k = 0; k < p; ++k) {
    EXPECT_NEAR(fit.coefficients[k], a[k], 1e-10 * a.cwiseAbs().maxCoeff()) << "c" << k;
    EXPECT_NEAR(fit.std_errors[k] / std::sqrt(covariance(k, k)), 1.0, 1e-10) << "c" << k;
  }
  EXPECT_NEAR(fit.residual_rms / std::sqrt(residual.squaredNorm() / n), 1.0, 1e-10);
}

TEST(PolynomialFit, RefusesTooFewOrIndistinctSamples) {
  const Eigen::VectorXd three = Eigen::VectorXd::LinSpaced(4, 0.0, 1.0);
  EXPECT_THROW(fit_polynomial(three, three, 3), InputError);  // 4 samples, 4 coefficients
  const Eigen::VectorXd same = Eigen::VectorXd::Constant(50, 0.02);
  const Eigen::VectorXd force = Eigen::VectorXd::LinSpaced(50, -1.0, 1.0);
  EXPECT_THROW(fit_polynomial(same, force, 3), InputError);  // one position: no cubic
}

}  // namespace
}  // namespace oscilab::analysis
