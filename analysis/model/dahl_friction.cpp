#include "analysis/model/dahl_friction.h"

#include <cmath>

namespace oscilab::analysis {
namespace {

const std::vector<NamedParameterTerm::Spec> kSpecs = {{"fc_n", true}, {"sigma0_n_m", true}};

}  // namespace

DahlFriction::DahlFriction(double fc_n, double sigma0_n_m)
    : NamedParameterTerm("presliding-hysteresis", kSpecs, {fc_n, sigma0_n_m}) {}

std::unique_ptr<ModelTerm> DahlFriction::from_json(const nlohmann::json& object,
                                                   const std::string& where) {
  return from_json_values(object, kSpecs, where, [](const std::vector<double>& v) {
    return std::make_unique<DahlFriction>(v[0], v[1]);
  });
}

double DahlFriction::force(double /*z_m*/, double /*z_dot_m_s*/, const double* state) const {
  return state ? value(0) * state[0] : 0.0;
}

TermPartials DahlFriction::partials(double, double, const double*) const { return {0.0, 0.0}; }

void DahlFriction::initial_state(double /*z_m*/, double* state) const { state[0] = 0.0; }

void DahlFriction::state_rate(double /*z_m*/, double z_dot_m_s, const double* state,
                              double* rate) const {
  const double direction = z_dot_m_s > 0.0 ? 1.0 : (z_dot_m_s < 0.0 ? -1.0 : 0.0);
  rate[0] = value(1) / value(0) * z_dot_m_s * (1.0 - state[0] * direction);
}

void DahlFriction::advance_state(double z0_m, double z_dot0_m_s, double z1_m, double z_dot1_m_s,
                                 double dt_s, double* state) const {
  advance_rate_independent(z0_m, z_dot0_m_s, z1_m, z_dot1_m_s, dt_s, state);
}

bool DahlFriction::advance_state_sensitivity(double z0_m, double z1_m, double* state,
                                             StateStepSensitivity& out) const {
  dahl_step(value(1) / value(0), z0_m, z1_m, state, out);  // κ = σ0/F_c
  return true;
}

double DahlFriction::force_d_state(double, double, const double*) const { return value(0); }

std::unique_ptr<ModelTerm> DahlFriction::clone() const {
  return std::make_unique<DahlFriction>(*this);
}

}  // namespace oscilab::analysis
