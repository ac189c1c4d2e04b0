#pragma once

#include "analysis/model/model_term.h"

namespace oscilab::analysis {

/// The paper's continuous friction law with a position-dependent normal load, eqs. (5)–(6):
///
///   D_f(z, ż) = f_d(z) [ tanh(4 ż / v_t) + (k_s − 1) u / (¼u² + ¾)² ],   u = ż / v_t,
///   f_d(z)    = max{0, α z² + β z + γ},           f_s(z) = (k_s − 1) f_d(z),  k_s ≥ 1.
///
/// The tanh part is a Coulomb law smoothed over the transition velocity v_t; the second part is
/// the static (Stribeck) excess, which peaks near |ż| = v_t and vanishes at high speed. The
/// viscous part c ż of eq. (5) is its own term (ViscousDamping). With α = β = 0 this is the
/// friction of the illustrative eq. (14).
///
/// JSON: {"type": "position-dependent-friction", "alpha_n_m2", "beta_n_m", "gamma_n", "ks",
///        "vt_m_s"}.
class PositionDependentFriction final : public ModelTerm {
 public:
  struct Parameters {
    double alpha_n_m2 = 0.0;  // α of eq. (6)
    double beta_n_m = 0.0;    // β
    double gamma_n = 0.0;     // γ = f_d(0)
    double ks = 1.0;          // k_s ≥ 1: static / dynamic friction ratio
    double vt_m_s = 1e-2;     // v_t > 0: transition velocity
  };

  /// Throws InputError when k_s < 1, v_t ≤ 0 or a value is not finite.
  explicit PositionDependentFriction(const Parameters& parameters);

  /// The parabola through three dynamic-friction values, as the paper's θ of eq. (9) gives them:
  /// f_d(z₋) = fd_minus_n, f_d(0) = fd_zero_n, f_d(z₊) = fd_plus_n. Requires z₋ < 0 < z₊.
  static Parameters from_three_points(double z_minus_m, double fd_minus_n, double fd_zero_n,
                                      double z_plus_m, double fd_plus_n, double ks, double vt_m_s);

  const Parameters& parameters() const { return parameters_; }

  /// f_d(z) of eq. (6) in N.
  double dynamic_friction_n(double z_m) const;
  /// The velocity shape g(ż) in brackets of eq. (7) and its derivative dg/dż.
  double velocity_shape(double z_dot_m_s) const;
  double velocity_shape_slope(double z_dot_m_s) const;

  std::string type() const override { return "position-dependent-friction"; }
  TermKind kind() const override { return TermKind::Dissipative; }
  double force(double z_m, double z_dot_m_s, const double* state) const override;
  TermPartials partials(double z_m, double z_dot_m_s, const double* state) const override;
  std::vector<std::string> parameter_names() const override;
  double parameter(const std::string& name) const override;
  void set_parameter(const std::string& name, double value) override;
  nlohmann::json to_json() const override;
  std::unique_ptr<ModelTerm> clone() const override;

 private:
  Parameters parameters_;
};

}  // namespace oscilab::analysis
