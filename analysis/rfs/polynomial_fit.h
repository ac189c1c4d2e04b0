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

/// fit_polynomial for samples that come in passes and are never held together (a day-long
/// record's stiffness slice): the same samples in the same order three times, one pass per
/// stage, then result().
///   1. add_to_range(x): the count, mean and extremes of x, for the centring and scaling;
///   2. add_to_normal_equations(x, y): the power sums; then solve();
///   3. add_to_residual(x, y): the residual variance of the solution, for the standard errors.
class PolynomialFitter {
 public:
  explicit PolynomialFitter(int degree);
  void add_to_range(double x);
  void add_to_normal_equations(double x, double y);
  /// Throws InputError as fit_polynomial does.
  void solve();
  void add_to_residual(double x, double y);
  /// The fit so far: after solve() its coefficients (what add_to_residual compares with);
  /// after the third pass its standard errors and residual too.
  PolynomialFit result() const;

 private:
  double u_of(double x) const { return (x - centre_) / scale_; }

  Eigen::Index p_;
  Eigen::Index n_ = 0;
  double sum_ = 0.0, min_ = 0.0, max_ = 0.0;
  double centre_ = 0.0, scale_ = 1.0;
  Eigen::VectorXd power_sums_, moments_;
  Eigen::VectorXd a_;  // coefficients in u
  Eigen::MatrixXd normal_inverse_;
  double residual_sq_ = 0.0;
};

}  // namespace oscilab::analysis
