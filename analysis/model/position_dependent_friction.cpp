#include "analysis/model/position_dependent_friction.h"

#include <algorithm>
#include <cmath>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {
namespace {

void validate(const PositionDependentFriction::Parameters& p) {
  const auto finite = [](double v) { return std::isfinite(v); };
  if (!finite(p.alpha_n_m2) || !finite(p.beta_n_m) || !finite(p.gamma_n) || !finite(p.ks) ||
      !finite(p.vt_m_s) || !finite(p.presliding_length_m)) {
    throw InputError("position-dependent-friction: parameters must be finite numbers");
  }
  if (p.ks < 1.0) {
    throw InputError("position-dependent-friction: ks: " + std::to_string(p.ks) +
                     " is below 1 (eq. (6) needs k_s >= 1)");
  }
  if (p.vt_m_s <= 0.0) {
    throw InputError("position-dependent-friction: vt_m_s: " + std::to_string(p.vt_m_s) +
                     " must be positive");
  }
  if (p.presliding_length_m < 0.0) {
    throw InputError("position-dependent-friction: presliding_length_m: " +
                     std::to_string(p.presliding_length_m) + " must be 0 (sliding) or positive");
  }
}

double sign_of(double v) { return v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0); }

}  // namespace

PositionDependentFriction::PositionDependentFriction(const Parameters& parameters)
    : parameters_(parameters) {
  validate(parameters_);
}

PositionDependentFriction::Parameters PositionDependentFriction::from_three_points(
    double z_minus_m, double fd_minus_n, double fd_zero_n, double z_plus_m, double fd_plus_n,
    double ks, double vt_m_s) {
  if (!(z_minus_m < 0.0 && z_plus_m > 0.0)) {
    throw InputError("position-dependent-friction: the three points need z- < 0 < z+");
  }
  // α z² + β z + γ through (z₋, f₋), (0, f₀), (z₊, f₊):  γ = f₀ and
  //   α z₋² + β z₋ = f₋ − f₀,  α z₊² + β z₊ = f₊ − f₀  (2×2 system, determinant z₋z₊(z₋ − z₊) ≠ 0).
  const double a = fd_minus_n - fd_zero_n;
  const double b = fd_plus_n - fd_zero_n;
  const double det = z_minus_m * z_plus_m * (z_minus_m - z_plus_m);
  Parameters p;
  p.alpha_n_m2 = (a * z_plus_m - b * z_minus_m) / det;
  p.beta_n_m = (b * z_minus_m * z_minus_m - a * z_plus_m * z_plus_m) / det;
  p.gamma_n = fd_zero_n;
  p.ks = ks;
  p.vt_m_s = vt_m_s;
  validate(p);
  return p;
}

double PositionDependentFriction::dynamic_friction_n(double z_m) const {
  const Parameters& p = parameters_;
  return std::max(0.0, (p.alpha_n_m2 * z_m + p.beta_n_m) * z_m + p.gamma_n);
}

double PositionDependentFriction::velocity_shape(double z_dot_m_s) const {
  const double u = z_dot_m_s / parameters_.vt_m_s;
  const double q = 0.25 * u * u + 0.75;
  return std::tanh(4.0 * u) + (parameters_.ks - 1.0) * u / (q * q);
}

double PositionDependentFriction::velocity_shape_slope(double z_dot_m_s) const {
  // d/dż tanh(4u) = (4/v_t) sech²(4u);  d/du [u q⁻²] = q⁻² − u² q⁻³ = (q − u²)/q³ = ¾(1 − u²)/q³.
  const double u = z_dot_m_s / parameters_.vt_m_s;
  const double q = 0.25 * u * u + 0.75;
  const double sech = 1.0 / std::cosh(4.0 * u);
  return (4.0 * sech * sech + (parameters_.ks - 1.0) * 0.75 * (1.0 - u * u) / (q * q * q)) /
         parameters_.vt_m_s;
}

double PositionDependentFriction::stribeck_shape(double z_dot_m_s) const {
  const double u = z_dot_m_s / parameters_.vt_m_s;
  const double q = 0.25 * u * u + 0.75;
  return (parameters_.ks - 1.0) * u / (q * q);
}

double PositionDependentFriction::stribeck_shape_slope(double z_dot_m_s) const {
  const double u = z_dot_m_s / parameters_.vt_m_s;
  const double q = 0.25 * u * u + 0.75;
  return (parameters_.ks - 1.0) * 0.75 * (1.0 - u * u) / (q * q * q) / parameters_.vt_m_s;
}

double PositionDependentFriction::force(double z_m, double z_dot_m_s, const double* state) const {
  if (!presliding()) return dynamic_friction_n(z_m) * velocity_shape(z_dot_m_s);
  // Presliding regime: the Coulomb part is f_d(z) s; without a state, the stateless part only.
  const double coulomb = state ? state[0] : 0.0;
  return dynamic_friction_n(z_m) * (coulomb + stribeck_shape(z_dot_m_s));
}

TermPartials PositionDependentFriction::partials(double z_m, double z_dot_m_s,
                                                 const double* state) const {
  const Parameters& p = parameters_;
  const double parabola = (p.alpha_n_m2 * z_m + p.beta_n_m) * z_m + p.gamma_n;
  const double dfd_dz = parabola > 0.0 ? 2.0 * p.alpha_n_m2 * z_m + p.beta_n_m : 0.0;
  if (!presliding()) {
    return {dfd_dz * velocity_shape(z_dot_m_s),
            dynamic_friction_n(z_m) * velocity_shape_slope(z_dot_m_s)};
  }
  // At a fixed state: f_d'(z) (s + Stribeck) and f_d(z) Stribeck'(ż); s's own dependence on the
  // path is the solvers' (HysteresisMarch).
  const double coulomb = state ? state[0] : 0.0;
  return {dfd_dz * (coulomb + stribeck_shape(z_dot_m_s)),
          dynamic_friction_n(z_m) * stribeck_shape_slope(z_dot_m_s)};
}

void PositionDependentFriction::initial_state(double /*z_m*/, double* state) const {
  state[0] = 0.0;
}

void PositionDependentFriction::state_rate(double /*z_m*/, double z_dot_m_s, const double* state,
                                           double* rate) const {
  rate[0] = z_dot_m_s * (1.0 - state[0] * sign_of(z_dot_m_s)) / parameters_.presliding_length_m;
}

void PositionDependentFriction::advance_state(double z0_m, double z_dot0_m_s, double z1_m,
                                              double z_dot1_m_s, double dt_s, double* state) const {
  advance_rate_independent(z0_m, z_dot0_m_s, z1_m, z_dot1_m_s, dt_s, state);
}

bool PositionDependentFriction::advance_state_sensitivity(double z0_m, double z1_m, double* state,
                                                          StateStepSensitivity& out) const {
  if (!presliding()) return false;
  dahl_step(1.0 / parameters_.presliding_length_m, z0_m, z1_m, state, out);  // κ = 1/δ
  return true;
}

double PositionDependentFriction::force_d_state(double z_m, double /*z_dot_m_s*/,
                                                const double* /*state*/) const {
  return presliding() ? dynamic_friction_n(z_m) : 0.0;
}

std::vector<std::string> PositionDependentFriction::parameter_names() const {
  return {"alpha_n_m2", "beta_n_m", "gamma_n", "ks", "vt_m_s", "presliding_length_m"};
}

double PositionDependentFriction::parameter(const std::string& name) const {
  const Parameters& p = parameters_;
  if (name == "alpha_n_m2") return p.alpha_n_m2;
  if (name == "beta_n_m") return p.beta_n_m;
  if (name == "gamma_n") return p.gamma_n;
  if (name == "ks") return p.ks;
  if (name == "vt_m_s") return p.vt_m_s;
  if (name == "presliding_length_m") return p.presliding_length_m;
  throw InputError("position-dependent-friction: unknown parameter \"" + name + "\"");
}

void PositionDependentFriction::set_parameter(const std::string& name, double value) {
  Parameters p = parameters_;
  if (name == "alpha_n_m2") {
    p.alpha_n_m2 = value;
  } else if (name == "beta_n_m") {
    p.beta_n_m = value;
  } else if (name == "gamma_n") {
    p.gamma_n = value;
  } else if (name == "ks") {
    p.ks = value;
  } else if (name == "vt_m_s") {
    p.vt_m_s = value;
  } else if (name == "presliding_length_m") {
    p.presliding_length_m = value;
  } else {
    throw InputError("position-dependent-friction: unknown parameter \"" + name + "\"");
  }
  validate(p);
  parameters_ = p;
}

nlohmann::json PositionDependentFriction::to_json() const {
  const Parameters& p = parameters_;
  nlohmann::json out = {{"type", type()},
                        {"alpha_n_m2", p.alpha_n_m2},
                        {"beta_n_m", p.beta_n_m},
                        {"gamma_n", p.gamma_n},
                        {"ks", p.ks},
                        {"vt_m_s", p.vt_m_s}};
  if (presliding()) out["presliding_length_m"] = p.presliding_length_m;  // the sliding law omits it
  return out;
}

std::unique_ptr<ModelTerm> PositionDependentFriction::clone() const {
  return std::make_unique<PositionDependentFriction>(*this);
}

}  // namespace oscilab::analysis
