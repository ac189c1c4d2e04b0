#include "analysis/rfs/polynomial_fit.h"

#include <cmath>

#include <Eigen/Dense>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {

double PolynomialFit::value(double x) const {
  double v = 0.0;
  for (Eigen::Index i = coefficients.size(); i-- > 0;) v = v * x + coefficients[i];
  return v;
}

PolynomialFit fit_polynomial(const Eigen::VectorXd& x, const Eigen::VectorXd& y, int degree) {
  const Eigen::Index n = x.size(), p = degree + 1;
  if (n <= p) {
    throw InputError("polynomial fit: " + std::to_string(n) + " samples for " + std::to_string(p) +
                     " coefficients");
  }
  const double centre = x.mean();
  const double scale = std::max(1e-300, (x.array() - centre).abs().maxCoeff());
  Eigen::MatrixXd design(n, p);
  for (Eigen::Index r = 0; r < n; ++r) {
    const double u = (x[r] - centre) / scale;
    double power = 1.0;
    for (Eigen::Index c = 0; c < p; ++c) {
      design(r, c) = power;
      power *= u;
    }
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(design);
  const Eigen::VectorXd a = qr.solve(y);  // coefficients in u
  const Eigen::VectorXd residual = design * a - y;
  const double variance = residual.squaredNorm() / static_cast<double>(n - p);
  const Eigen::MatrixXd normal = design.transpose() * design;
  const Eigen::MatrixXd cov_u = variance * normal.inverse();

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
  fit.residual_rms = std::sqrt(residual.squaredNorm() / static_cast<double>(n));
  fit.samples = n;
  return fit;
}

}  // namespace oscilab::analysis
