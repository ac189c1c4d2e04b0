#include "analysis/model/coulomb_friction.h"

#include <cmath>

namespace oscilab::analysis {
namespace {

const std::vector<NamedParameterTerm::Spec> kCoulombSpecs = {{"fc_n", false}, {"v_eps_m_s", true}};
const std::vector<NamedParameterTerm::Spec> kStribeckSpecs = {{"fs_n", false}, {"vs_m_s", true}};

}  // namespace

CoulombFriction::CoulombFriction(double fc_n, double v_eps_m_s)
    : NamedParameterTerm("coulomb-friction", kCoulombSpecs, {fc_n, v_eps_m_s}) {}

std::unique_ptr<ModelTerm> CoulombFriction::from_json(const nlohmann::json& object,
                                                      const std::string& where) {
  return from_json_values(object, kCoulombSpecs, where, [](const std::vector<double>& v) {
    return std::make_unique<CoulombFriction>(v[0], v[1]);
  });
}

double CoulombFriction::force(double /*z_m*/, double z_dot_m_s, const double* /*state*/) const {
  return value(0) * std::tanh(z_dot_m_s / value(1));
}

TermPartials CoulombFriction::partials(double /*z_m*/, double z_dot_m_s,
                                       const double* /*state*/) const {
  const double t = std::tanh(z_dot_m_s / value(1));
  return {0.0, value(0) * (1.0 - t * t) / value(1)};
}

std::unique_ptr<ModelTerm> CoulombFriction::clone() const {
  return std::make_unique<CoulombFriction>(*this);
}

StribeckFriction::StribeckFriction(double fs_n, double vs_m_s)
    : NamedParameterTerm("stribeck-friction", kStribeckSpecs, {fs_n, vs_m_s}) {}

std::unique_ptr<ModelTerm> StribeckFriction::from_json(const nlohmann::json& object,
                                                       const std::string& where) {
  return from_json_values(object, kStribeckSpecs, where, [](const std::vector<double>& v) {
    return std::make_unique<StribeckFriction>(v[0], v[1]);
  });
}

double StribeckFriction::force(double /*z_m*/, double z_dot_m_s, const double* /*state*/) const {
  const double u = z_dot_m_s / value(1);
  const double d = 0.25 * u * u + 0.75;
  return value(0) * u / (d * d);
}

TermPartials StribeckFriction::partials(double /*z_m*/, double z_dot_m_s,
                                        const double* /*state*/) const {
  // d/du [u d⁻²] = d⁻² − 2u d⁻³ (dd/du) with dd/du = u/2: 1/d² − u²/d³.
  const double u = z_dot_m_s / value(1);
  const double d = 0.25 * u * u + 0.75;
  return {0.0, value(0) * (1.0 / (d * d) - u * u / (d * d * d)) / value(1)};
}

std::unique_ptr<ModelTerm> StribeckFriction::clone() const {
  return std::make_unique<StribeckFriction>(*this);
}

}  // namespace oscilab::analysis
