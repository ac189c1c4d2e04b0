#include "analysis/model/velocity_power_damping.h"

#include <cmath>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {
namespace {

int checked_power(int power) {
  if (power != 2 && power != 3) {
    throw InputError("velocity-power damping: power " + std::to_string(power) + " is not 2 or 3");
  }
  return power;
}

std::vector<NamedParameterTerm::Spec> specs(int power) {
  return {{power == 2 ? "c2_ns2_m2" : "c3_ns3_m3", false}};
}

std::string type_of(int power) { return power == 2 ? "quadratic-damping" : "cubic-damping"; }

}  // namespace

VelocityPowerDamping::VelocityPowerDamping(int power, double coefficient)
    : NamedParameterTerm(type_of(checked_power(power)), specs(power), {coefficient}),
      power_(power) {}

std::unique_ptr<ModelTerm> VelocityPowerDamping::from_json(int power, const nlohmann::json& object,
                                                           const std::string& where) {
  return from_json_values(object, specs(power), where, [power](const std::vector<double>& v) {
    return std::make_unique<VelocityPowerDamping>(power, v[0]);
  });
}

std::string VelocityPowerDamping::type() const { return type_of(power_); }

double VelocityPowerDamping::force(double /*z_m*/, double z_dot_m_s,
                                   const double* /*state*/) const {
  const double speed = std::abs(z_dot_m_s);
  return value(0) * z_dot_m_s * (power_ == 2 ? speed : speed * speed);
}

TermPartials VelocityPowerDamping::partials(double /*z_m*/, double z_dot_m_s,
                                            const double* /*state*/) const {
  const double speed = std::abs(z_dot_m_s);
  // d/dż (ż |ż|^(p−1)) = p |ż|^(p−1).
  return {0.0, value(0) * power_ * (power_ == 2 ? speed : speed * speed)};
}

std::unique_ptr<ModelTerm> VelocityPowerDamping::clone() const {
  return std::make_unique<VelocityPowerDamping>(*this);
}

}  // namespace oscilab::analysis
