#include "analysis/model/viscous_damping.h"

#include <cmath>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {
namespace {

double checked(double c_ns_m) {
  if (!std::isfinite(c_ns_m) || c_ns_m < 0.0) {
    throw InputError("viscous-damping: c_ns_m: " + std::to_string(c_ns_m) +
                     " must be a finite number >= 0");
  }
  return c_ns_m;
}

}  // namespace

ViscousDamping::ViscousDamping(double c_ns_m) : c_ns_m_(checked(c_ns_m)) {}

double ViscousDamping::force(double /*z_m*/, double z_dot_m_s, const double* /*state*/) const {
  return c_ns_m_ * z_dot_m_s;
}

TermPartials ViscousDamping::partials(double /*z_m*/, double /*z_dot_m_s*/,
                                      const double* /*state*/) const {
  return {0.0, c_ns_m_};
}

double ViscousDamping::parameter(const std::string& name) const {
  if (name == "c_ns_m") return c_ns_m_;
  throw InputError("viscous-damping: unknown parameter \"" + name + "\"");
}

void ViscousDamping::set_parameter(const std::string& name, double value) {
  if (name != "c_ns_m") throw InputError("viscous-damping: unknown parameter \"" + name + "\"");
  c_ns_m_ = checked(value);
}

nlohmann::json ViscousDamping::to_json() const { return {{"type", type()}, {"c_ns_m", c_ns_m_}}; }

std::unique_ptr<ModelTerm> ViscousDamping::clone() const {
  return std::make_unique<ViscousDamping>(*this);
}

}  // namespace oscilab::analysis
