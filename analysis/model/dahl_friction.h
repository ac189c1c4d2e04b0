#pragma once

#include <memory>

#include "analysis/model/named_parameter_term.h"

namespace oscilab::analysis {

/// Presliding hysteresis by the Dahl model (Dahl 1968, "A solid friction model"; the first-order
/// form of Olsson et al. 1998, "Friction models and friction compensation"): the friction force
/// F = F_c s follows the displacement with a presliding stiffness σ0 that fades as F nears F_c,
///
///   dF/dz = σ0 (1 − (F/F_c) sgn ż),   i.e.   ds/dt = (σ0/F_c) ż (1 − s sgn ż),  s ∈ [−1, 1].
///
/// Rate-independent: s depends on the path of z only, and along a monotone stretch Δz it relaxes
/// exactly, s₁ = d + (s₀ − d) e^(−σ0 |Δz| / F_c) with d = sgn Δz (advance_state). A symmetric
/// cycle z = Z sin ωt settles on the loop s = ±tanh(κZ) at the turning points (κ = σ0/F_c) and
/// dissipates, exactly,
///
///   ∮ F dz = 4 F_c (Z − tanh(κZ)/κ):
///
/// an elastic-hysteretic loop ≈ (4/3) σ0² Z³ / F_c for Z ≪ F_c/σ0 (∝ Z³), a Coulomb rectangle
/// 4 F_c Z − 4 F_c²/σ0 for Z ≫ F_c/σ0 (∝ Z¹).
/// JSON {"type": "presliding-hysteresis", "fc_n", "sigma0_n_m"}; the state at rest is s = 0.
class DahlFriction final : public NamedParameterTerm {
 public:
  DahlFriction(double fc_n, double sigma0_n_m);  // throws InputError: F_c ≤ 0, σ0 ≤ 0
  static std::unique_ptr<ModelTerm> from_json(const nlohmann::json& object,
                                              const std::string& where);
  std::string type() const override { return "presliding-hysteresis"; }
  TermKind kind() const override { return TermKind::Dissipative; }
  /// F_c s; 0 without a state (nullptr: the element is not tracked, as in a stateless solver).
  double force(double z_m, double z_dot_m_s, const double* state) const override;
  /// The force depends on the state only: both partials are 0 (solvers that track the state
  /// handle its dependence on the path, see HysteresisMarch).
  TermPartials partials(double z_m, double z_dot_m_s, const double* state) const override;
  int state_size() const override { return 1; }
  void initial_state(double z_m, double* state) const override;
  void state_rate(double z_m, double z_dot_m_s, const double* state, double* rate) const override;
  void advance_state(double z0_m, double z_dot0_m_s, double z1_m, double z_dot1_m_s, double dt_s,
                     double* state) const override;
  /// The exact update with s₁ = d + (s₀ − d) a, a = e^(−κ|Δz|), d = sgn Δz:
  /// ∂s₁/∂s₀ = a and ∂s₁/∂z₁ = −∂s₁/∂z₀ = κ a (1 − d s₀) (at Δz = 0 the mean of both sides, κ).
  bool advance_state_sensitivity(double z0_m, double z1_m, double* state,
                                 StateStepSensitivity& out) const override;
  double force_d_state(double z_m, double z_dot_m_s, const double* state) const override;
  std::unique_ptr<ModelTerm> clone() const override;
};

}  // namespace oscilab::analysis
