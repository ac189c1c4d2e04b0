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
/// **Presliding regime** (optional, presliding length δ > 0): the paper's §1 separates presliding,
/// a hysteretic function of the displacement, from sliding. With δ > 0 the Coulomb part
/// f_d(z) tanh(4ż/v_t) becomes f_d(z) s, with s a Dahl state of the contact itself (Dahl 1968):
///
///   ds/dz = (1 − s sgn ż) / δ,   s ∈ [−1, 1],
///
/// so that after a reversal the friction crosses from one sliding value to the other over a few δ
/// of travel; along a monotone stretch Δz, s₁ = d + (s₀ − d) e^(−|Δz|/δ), d = sgn Δz, exactly. The
/// Stribeck excess stays the velocity law it is. δ → 0 recovers a sliding law (s = sgn ż, which
/// tanh(4ż/v_t) smooths over |ż| ≲ v_t/4); δ = 0 is the paper's law itself and holds no state.
/// Without a state (force(z, ż, nullptr)) the term gives its stateless part, the Stribeck excess:
/// solvers that track the state add the rest (ModelTerm, "force without a state").
///
/// JSON: {"type": "position-dependent-friction", "alpha_n_m2", "beta_n_m", "gamma_n", "ks",
///        "vt_m_s"} and, for the presliding regime, "presliding_length_m".
class PositionDependentFriction final : public ModelTerm {
 public:
  struct Parameters {
    double alpha_n_m2 = 0.0;           // α of eq. (6)
    double beta_n_m = 0.0;             // β
    double gamma_n = 0.0;              // γ = f_d(0)
    double ks = 1.0;                   // k_s ≥ 1: static / dynamic friction ratio
    double vt_m_s = 1e-2;              // v_t > 0: transition velocity
    double presliding_length_m = 0.0;  // δ ≥ 0: 0 the sliding law of eq. (5), > 0 presliding
  };

  /// Throws InputError when k_s < 1, v_t ≤ 0, δ < 0 or a value is not finite.
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
  /// The Stribeck excess alone, (k_s − 1) u / (¼u² + ¾)², and its slope d/dż.
  double stribeck_shape(double z_dot_m_s) const;
  double stribeck_shape_slope(double z_dot_m_s) const;
  bool presliding() const { return parameters_.presliding_length_m > 0.0; }

  std::string type() const override { return "position-dependent-friction"; }
  TermKind kind() const override { return TermKind::Dissipative; }
  double force(double z_m, double z_dot_m_s, const double* state) const override;
  TermPartials partials(double z_m, double z_dot_m_s, const double* state) const override;
  /// One state (the contact's Dahl state s) in the presliding regime, none otherwise.
  int state_size() const override { return presliding() ? 1 : 0; }
  void initial_state(double z_m, double* state) const override;
  void state_rate(double z_m, double z_dot_m_s, const double* state, double* rate) const override;
  void advance_state(double z0_m, double z_dot0_m_s, double z1_m, double z_dot1_m_s, double dt_s,
                     double* state) const override;
  /// The exact update, as DahlFriction's with κ = 1/δ.
  bool advance_state_sensitivity(double z0_m, double z1_m, double* state,
                                 StateStepSensitivity& out) const override;
  double force_d_state(double z_m, double z_dot_m_s, const double* state) const override;
  std::vector<std::string> parameter_names() const override;
  double parameter(const std::string& name) const override;
  void set_parameter(const std::string& name, double value) override;
  nlohmann::json to_json() const override;
  std::unique_ptr<ModelTerm> clone() const override;

 private:
  Parameters parameters_;
};

}  // namespace oscilab::analysis
