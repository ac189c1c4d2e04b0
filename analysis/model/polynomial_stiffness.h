#pragma once

#include <vector>

#include "analysis/model/model_term.h"

namespace oscilab::analysis {

/// Elastic restoring force as a polynomial, K(z) = Σ_i c_i z^i (c_i in N/m^i).
///
/// The paper's eq. (2), K(z) = k3 z³ + k2 z² − k1 z + k0, is coefficients {k0, −k1, k2, k3}: note
/// the sign of the linear term, negative stiffness at the origin for k1 > 0. Higher powers
/// (quintic stiffness) are more coefficients.
///
/// JSON: {"type": "polynomial-stiffness", "coefficients": [c0, c1, c2, ...]}.
class PolynomialStiffness final : public ModelTerm {
 public:
  /// Throws InputError when empty or not finite.
  explicit PolynomialStiffness(std::vector<double> coefficients);

  /// From the paper's eq. (2) parameters.
  static PolynomialStiffness from_paper(double k3_n_m3, double k2_n_m2, double k1_n_m, double k0_n);

  const std::vector<double>& coefficients() const { return coefficients_; }

  std::string type() const override { return "polynomial-stiffness"; }
  TermKind kind() const override { return TermKind::Elastic; }
  double force(double z_m, double z_dot_m_s, const double* state) const override;
  TermPartials partials(double z_m, double z_dot_m_s, const double* state) const override;
  double potential_j(double z_m) const override;  // Eq. (3): U = Σ c_i z^(i+1) / (i+1)
  std::vector<std::string> parameter_names() const override;
  double parameter(const std::string& name) const override;
  void set_parameter(const std::string& name, double value) override;
  nlohmann::json to_json() const override;
  std::unique_ptr<ModelTerm> clone() const override;

  /// dK/dz at z: the linear stiffness about z (U''(z) in eq. (4)).
  double stiffness_n_m(double z_m) const;

 private:
  std::vector<double> coefficients_;
};

}  // namespace oscilab::analysis
