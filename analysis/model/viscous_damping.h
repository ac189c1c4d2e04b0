#pragma once

#include "analysis/model/model_term.h"

namespace oscilab::analysis {

/// Linear viscous damping c ż, the last part of eq. (5).
/// JSON: {"type": "viscous-damping", "c_ns_m": c}.
class ViscousDamping final : public ModelTerm {
 public:
  explicit ViscousDamping(double c_ns_m);  // throws InputError when c < 0 or not finite

  double c_ns_m() const { return c_ns_m_; }

  std::string type() const override { return "viscous-damping"; }
  TermKind kind() const override { return TermKind::Dissipative; }
  double force(double z_m, double z_dot_m_s, const double* state) const override;
  TermPartials partials(double z_m, double z_dot_m_s, const double* state) const override;
  std::vector<std::string> parameter_names() const override { return {"c_ns_m"}; }
  double parameter(const std::string& name) const override;
  void set_parameter(const std::string& name, double value) override;
  nlohmann::json to_json() const override;
  std::unique_ptr<ModelTerm> clone() const override;

 private:
  double c_ns_m_;
};

}  // namespace oscilab::analysis
