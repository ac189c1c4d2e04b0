#pragma once

#include <memory>

#include "analysis/model/named_parameter_term.h"

namespace oscilab::analysis {

/// Position-independent Coulomb friction, smoothed over a small velocity: F = F_c tanh(ż / v_ε).
/// Dissipates 4 F_c Z per harmonic cycle of amplitude Z when ωZ ≫ v_ε (∝ Z¹).
/// JSON {"type": "coulomb-friction", "fc_n", "v_eps_m_s"}.
class CoulombFriction final : public NamedParameterTerm {
 public:
  CoulombFriction(double fc_n, double v_eps_m_s);  // throws InputError: fc < 0, v_ε ≤ 0
  static std::unique_ptr<ModelTerm> from_json(const nlohmann::json& object,
                                              const std::string& where);
  std::string type() const override { return "coulomb-friction"; }
  TermKind kind() const override { return TermKind::Dissipative; }
  double force(double z_m, double z_dot_m_s, const double* state) const override;
  TermPartials partials(double z_m, double z_dot_m_s, const double* state) const override;
  std::unique_ptr<ModelTerm> clone() const override;
};

/// A Stribeck excess on top of the model's friction: F = f_s u / (¼u² + ¾)², u = ż / v_s, the
/// static part of eq. (5) with its own force and velocity scale (largest, f_s, at |ż| = v_s; it
/// vanishes at high speed). JSON {"type": "stribeck-friction", "fs_n", "vs_m_s"}.
class StribeckFriction final : public NamedParameterTerm {
 public:
  StribeckFriction(double fs_n, double vs_m_s);  // throws InputError: f_s < 0, v_s ≤ 0
  static std::unique_ptr<ModelTerm> from_json(const nlohmann::json& object,
                                              const std::string& where);
  std::string type() const override { return "stribeck-friction"; }
  TermKind kind() const override { return TermKind::Dissipative; }
  double force(double z_m, double z_dot_m_s, const double* state) const override;
  TermPartials partials(double z_m, double z_dot_m_s, const double* state) const override;
  std::unique_ptr<ModelTerm> clone() const override;
};

}  // namespace oscilab::analysis
