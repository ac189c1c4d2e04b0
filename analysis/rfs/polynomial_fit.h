#pragma once

#include <Eigen/Core>

namespace oscilab::analysis {

/// Least-squares polynomial y ≈ Σ_i c_i x^i with standard errors from the covariance
/// σ² (AᵀA)⁻¹, σ² the residual variance with the fit's degrees of freedom removed. The design is
/// centred and scaled internally ((x − x̄)/s) for conditioning; the coefficients are returned for
/// the plain powers of x.
struct PolynomialFit {
  Eigen::VectorXd coefficients;  // c_0 .. c_degree
  Eigen::VectorXd std_errors;
  double residual_rms = 0.0;
  Eigen::Index samples = 0;
  double value(double x) const;
};

/// Throws InputError when there are fewer samples than coefficients, or when the samples do not
/// determine the polynomial (fewer distinct x than coefficients).
PolynomialFit fit_polynomial(Eigen::Ref<const Eigen::VectorXd> x,
                             Eigen::Ref<const Eigen::VectorXd> y, int degree);

}  // namespace oscilab::analysis
