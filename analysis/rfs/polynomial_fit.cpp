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

PolynomialFitter::PolynomialFitter(int degree)
    : p_(degree + 1),
      power_sums_(Eigen::VectorXd::Zero(2 * (degree + 1) - 1)),
      moments_(Eigen::VectorXd::Zero(degree + 1)) {}

void PolynomialFitter::add_to_range(double x) {
  min_ = n_ == 0 ? x : std::min(min_, x);
  max_ = n_ == 0 ? x : std::max(max_, x);
  sum_ += x;
  ++n_;
  // The centre and scale as far as seen: the second pass's u ∈ [−1, 1].
  centre_ = sum_ / static_cast<double>(n_);
  scale_ = std::max(1e-300, std::max(max_ - centre_, centre_ - min_));
}

// The normal equations in u = (x − x̄)/s ∈ [−1, 1], from one pass of power sums:
// (AᵀA)_ij = Σ u^(i+j) and (Aᵀy)_i = Σ u^i y, so no n × p design matrix is made. On [−1, 1]
// the moment matrix of a cubic has a condition number of some 10³, so the solution carries
// about 1e-13 relative rounding (the QR of the design, a second method, agrees to that:
// tests/analysis/rfs/polynomial_fit_test.cpp) at a fraction of the cost for a slice's tens of
// thousands of samples.
void PolynomialFitter::add_to_normal_equations(double x, double y) {
  const double u = u_of(x);
  double power = 1.0;
  for (Eigen::Index k = 0; k < 2 * p_ - 1; ++k) {
    power_sums_[k] += power;
    if (k < p_) moments_[k] += power * y;
    power *= u;
  }
}

void PolynomialFitter::solve() {
  if (n_ <= p_) {
    throw InputError("polynomial fit: " + std::to_string(n_) + " samples for " +
                     std::to_string(p_) + " coefficients");
  }
  Eigen::MatrixXd normal(p_, p_);
  for (Eigen::Index i = 0; i < p_; ++i) {
    for (Eigen::Index j = 0; j < p_; ++j) normal(i, j) = power_sums_[i + j];
  }
  const Eigen::LDLT<Eigen::MatrixXd> factor(normal);
  // A pivot at rounding level against the largest: fewer distinct x than coefficients.
  const Eigen::VectorXd pivots = factor.vectorD();
  if (factor.info() != Eigen::Success || !(pivots.minCoeff() > 1e-12 * pivots.maxCoeff())) {
    throw InputError("polynomial fit: the samples do not determine a polynomial of degree " +
                     std::to_string(p_ - 1));
  }
  a_ = factor.solve(moments_);
  normal_inverse_ = factor.solve(Eigen::MatrixXd::Identity(p_, p_));
}

void PolynomialFitter::add_to_residual(double x, double y) {
  const double u = u_of(x);
  double value = 0.0;
  for (Eigen::Index k = p_; k-- > 0;) value = value * u + a_[k];
  residual_sq_ += (value - y) * (value - y);
}

PolynomialFit PolynomialFitter::result() const {
  const double variance = residual_sq_ / static_cast<double>(n_ - p_);
  const Eigen::MatrixXd cov_u = variance * normal_inverse_;
  // c = T a with x-powers: u^j = ((x − x̄)/s)^j = Σ_i C(j,i) x^i (−x̄)^{j−i} / s^j.
  Eigen::MatrixXd transform = Eigen::MatrixXd::Zero(p_, p_);
  for (Eigen::Index j = 0; j < p_; ++j) {
    double binomial = 1.0;
    for (Eigen::Index i = 0; i <= j; ++i) {
      if (i > 0) binomial = binomial * static_cast<double>(j - i + 1) / static_cast<double>(i);
      transform(i, j) = binomial * std::pow(-centre_, static_cast<double>(j - i)) /
                        std::pow(scale_, static_cast<double>(j));
    }
  }
  PolynomialFit fit;
  fit.coefficients = transform * a_;
  const Eigen::MatrixXd cov = transform * cov_u * transform.transpose();
  fit.std_errors = cov.diagonal().cwiseMax(0.0).cwiseSqrt();
  fit.residual_rms = std::sqrt(residual_sq_ / static_cast<double>(n_));
  fit.samples = n_;
  return fit;
}

PolynomialFit fit_polynomial(Eigen::Ref<const Eigen::VectorXd> x,
                             Eigen::Ref<const Eigen::VectorXd> y, int degree) {
  PolynomialFitter fitter(degree);
  for (Eigen::Index r = 0; r < x.size(); ++r) fitter.add_to_range(x[r]);
  for (Eigen::Index r = 0; r < x.size(); ++r) fitter.add_to_normal_equations(x[r], y[r]);
  fitter.solve();
  for (Eigen::Index r = 0; r < x.size(); ++r) fitter.add_to_residual(x[r], y[r]);
  return fitter.result();
}

}  // namespace oscilab::analysis
