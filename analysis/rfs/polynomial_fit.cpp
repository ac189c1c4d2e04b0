#include "analysis/rfs/polynomial_fit.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Dense>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {

double PolynomialFit::value(double x) const {
  double v = 0.0;
  for (Eigen::Index i = coefficients.size(); i-- > 0;) v = v * x + coefficients[i];
  return v;
}

PolynomialFit fit_polynomial(Eigen::Ref<const Eigen::VectorXd> x,
                             Eigen::Ref<const Eigen::VectorXd> y, int degree) {
  const Eigen::Index n = x.size(), p = degree + 1;
  if (n <= p) {
    throw InputError("polynomial fit: " + std::to_string(n) + " samples for " + std::to_string(p) +
                     " coefficients");
  }
  const double centre = x.mean();
  const double scale = std::max(1e-300, (x.array() - centre).abs().maxCoeff());
  // The normal equations in u = (x − x̄)/s ∈ [−1, 1], from one pass of power sums:
  // (AᵀA)_ij = Σ u^(i+j) and (Aᵀy)_i = Σ u^i y, so no n × p design matrix is made. On [−1, 1]
  // the moment matrix of a cubic has a condition number of some 10³, so the solution carries
  // about 1e-13 relative rounding (the QR of the design, a second method, agrees to that:
  // tests/analysis/rfs/polynomial_fit_test.cpp) at a fraction of the cost for a slice's tens of
  // thousands of samples.
  Eigen::VectorXd power_sums = Eigen::VectorXd::Zero(2 * p - 1);
  Eigen::VectorXd moments = Eigen::VectorXd::Zero(p);
  for (Eigen::Index r = 0; r < n; ++r) {
    const double u = (x[r] - centre) / scale;
    double power = 1.0;
    for (Eigen::Index k = 0; k < 2 * p - 1; ++k) {
      power_sums[k] += power;
      if (k < p) moments[k] += power * y[r];
      power *= u;
    }
  }
  Eigen::MatrixXd normal(p, p);
  for (Eigen::Index i = 0; i < p; ++i) {
    for (Eigen::Index j = 0; j < p; ++j) normal(i, j) = power_sums[i + j];
  }
  const Eigen::LDLT<Eigen::MatrixXd> factor(normal);
  // A pivot at rounding level against the largest: fewer distinct x than coefficients.
  const Eigen::VectorXd pivots = factor.vectorD();
  if (factor.info() != Eigen::Success || !(pivots.minCoeff() > 1e-12 * pivots.maxCoeff())) {
    throw InputError("polynomial fit: the samples do not determine a polynomial of degree " +
                     std::to_string(degree));
  }
  const Eigen::VectorXd a = factor.solve(moments);  // coefficients in u
  double residual_sq = 0.0;
  for (Eigen::Index r = 0; r < n; ++r) {
    const double u = (x[r] - centre) / scale;
    double value = 0.0;
    for (Eigen::Index k = p; k-- > 0;) value = value * u + a[k];
    residual_sq += (value - y[r]) * (value - y[r]);
  }
  const double variance = residual_sq / static_cast<double>(n - p);
  const Eigen::MatrixXd cov_u = variance * factor.solve(Eigen::MatrixXd::Identity(p, p));

  // c = T a with x-powers: u^j = ((x − x̄)/s)^j = Σ_i C(j,i) x^i (−x̄)^{j−i} / s^j.
  Eigen::MatrixXd transform = Eigen::MatrixXd::Zero(p, p);
  for (Eigen::Index j = 0; j < p; ++j) {
    double binomial = 1.0;
    for (Eigen::Index i = 0; i <= j; ++i) {
      if (i > 0) binomial = binomial * static_cast<double>(j - i + 1) / static_cast<double>(i);
      transform(i, j) = binomial * std::pow(-centre, static_cast<double>(j - i)) /
                        std::pow(scale, static_cast<double>(j));
    }
  }
  PolynomialFit fit;
  fit.coefficients = transform * a;
  const Eigen::MatrixXd cov = transform * cov_u * transform.transpose();
  fit.std_errors = cov.diagonal().cwiseMax(0.0).cwiseSqrt();
  fit.residual_rms = std::sqrt(residual_sq / static_cast<double>(n));
  fit.samples = n;
  return fit;
}

}  // namespace oscilab::analysis
