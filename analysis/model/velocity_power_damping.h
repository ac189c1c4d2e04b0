#pragma once

#include <memory>

#include "analysis/model/named_parameter_term.h"

namespace oscilab::analysis {

/// Damping by a power of the velocity, F = c_p ż |ż|^(p−1): quadratic damping (p = 2, fluid drag
/// at high Reynolds number; JSON {"type": "quadratic-damping", "c2_ns2_m2"}) and cubic damping
/// (p = 3; {"type": "cubic-damping", "c3_ns3_m3"}). Over a harmonic cycle of amplitude Z at ω it
/// dissipates c_p (ωZ)^p Z ∮|sin|^(p+1) dθ: ∝ Z³ for p = 2 (8/3 c2 ω² Z³) and ∝ Z⁴ for p = 3
/// (3π/4 c3 ω³ Z⁴).
class VelocityPowerDamping final : public NamedParameterTerm {
 public:
  /// power 2 or 3; throws InputError for another power or c < 0.
  VelocityPowerDamping(int power, double coefficient);
  static std::unique_ptr<ModelTerm> from_json(int power, const nlohmann::json& object,
                                              const std::string& where);

  int power() const { return power_; }
  std::string type() const override;
  TermKind kind() const override { return TermKind::Dissipative; }
  double force(double z_m, double z_dot_m_s, const double* state) const override;
  TermPartials partials(double z_m, double z_dot_m_s, const double* state) const override;
  std::unique_ptr<ModelTerm> clone() const override;

 private:
  int power_;
};

}  // namespace oscilab::analysis
