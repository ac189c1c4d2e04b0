#include "analysis/model/model_term.h"

#include <cmath>
#include <vector>

namespace oscilab::analysis {

HermiteTurn hermite_turning_point(double z0_m, double z_dot0_m_s, double z1_m, double z_dot1_m_s,
                                  double dt_s) {
  HermiteTurn turn;
  if (!(z_dot0_m_s * z_dot1_m_s < 0.0) || !(dt_s > 0.0)) return turn;
  // p(θ) = h00 z0 + h10 ż0 dt + h01 z1 + h11 ż1 dt; p'(θ) = a θ² + b θ + c changes sign on (0, 1).
  const double v0 = z_dot0_m_s * dt_s, v1 = z_dot1_m_s * dt_s, dz = z0_m - z1_m;
  const double a = 6.0 * dz + 3.0 * v0 + 3.0 * v1;
  const double b = -6.0 * dz - 4.0 * v0 - 2.0 * v1;
  const double c = v0;
  const auto slope = [&](double t) { return (a * t + b) * t + c; };
  // Bisection on the sign change (p'(0) = v0 and p'(1) = v1 differ in sign): 60 halvings reach
  // rounding, and no case of the quadratic's roots needs handling apart.
  double lo = 0.0, hi = 1.0;
  const bool rising_at_lo = c > 0.0;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    if ((slope(mid) > 0.0) == rising_at_lo) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  const double t = 0.5 * (lo + hi), t2 = t * t, t3 = t2 * t;
  const double h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + t, h01 = -2 * t3 + 3 * t2,
               h11 = t3 - t2;
  turn.inside = true;
  turn.theta = t;
  turn.z_m = h00 * z0_m + h10 * v0 + h01 * z1_m + h11 * v1;
  turn.d_z0 = h00;
  turn.d_z1 = h01;
  turn.d_v0 = h10 * dt_s;
  turn.d_v1 = h11 * dt_s;
  return turn;
}

void dahl_step(double kappa_1_m, double z0_m, double z1_m, double* state,
               StateStepSensitivity& out) {
  const double dz = z1_m - z0_m;
  if (dz == 0.0) {
    out = {1.0, -kappa_1_m, kappa_1_m, 0.0, true};
    return;
  }
  const double d = dz > 0.0 ? 1.0 : -1.0;
  const double log_a = -kappa_1_m * std::abs(dz);
  const double a = std::exp(log_a);
  const double slope = kappa_1_m * a * (1.0 - d * state[0]);
  state[0] = d + (state[0] - d) * a;
  out = {a, -slope, slope, log_a, true};
}

void ModelTerm::advance_rate_independent(double z0_m, double z_dot0_m_s, double z1_m,
                                         double z_dot1_m_s, double dt_s, double* state) const {
  StateStepSensitivity unused;
  const HermiteTurn turn = hermite_turning_point(z0_m, z_dot0_m_s, z1_m, z_dot1_m_s, dt_s);
  if (turn.inside) {
    advance_state_sensitivity(z0_m, turn.z_m, state, unused);
    advance_state_sensitivity(turn.z_m, z1_m, state, unused);
  } else {
    advance_state_sensitivity(z0_m, z1_m, state, unused);
  }
}

void ModelTerm::advance_state(double z0_m, double z_dot0_m_s, double z1_m, double z_dot1_m_s,
                              double dt_s, double* state) const {
  const int n = state_size();
  if (n == 0 || dt_s <= 0.0) return;
  // Cubic Hermite path z(θ), θ ∈ [0, 1], through both ends with both slopes (ż dt).
  const auto path = [&](double t, double& z, double& z_dot) {
    const double t2 = t * t, t3 = t2 * t;
    const double h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + t, h01 = -2 * t3 + 3 * t2,
                 h11 = t3 - t2;
    const double d00 = 6 * t2 - 6 * t, d10 = 3 * t2 - 4 * t + 1, d01 = -6 * t2 + 6 * t,
                 d11 = 3 * t2 - 2 * t;
    z = h00 * z0_m + h10 * z_dot0_m_s * dt_s + h01 * z1_m + h11 * z_dot1_m_s * dt_s;
    z_dot = (d00 * z0_m + d01 * z1_m) / dt_s + d10 * z_dot0_m_s + d11 * z_dot1_m_s;
  };
  constexpr int kSubSteps = 8;
  const double h = 1.0 / kSubSteps;
  std::vector<double> k1(n), k2(n), k3(n), k4(n), tmp(n);
  const auto rate = [&](double t, const double* s, double* out) {
    double z = 0.0, z_dot = 0.0;
    path(t, z, z_dot);
    state_rate(z, z_dot, s, out);
  };
  for (int step = 0; step < kSubSteps; ++step) {
    const double t = step * h;
    rate(t, state, k1.data());
    for (int i = 0; i < n; ++i) tmp[i] = state[i] + 0.5 * h * dt_s * k1[i];
    rate(t + 0.5 * h, tmp.data(), k2.data());
    for (int i = 0; i < n; ++i) tmp[i] = state[i] + 0.5 * h * dt_s * k2[i];
    rate(t + 0.5 * h, tmp.data(), k3.data());
    for (int i = 0; i < n; ++i) tmp[i] = state[i] + h * dt_s * k3[i];
    rate(t + h, tmp.data(), k4.data());
    for (int i = 0; i < n; ++i) {
      state[i] += h * dt_s / 6.0 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    }
  }
}

}  // namespace oscilab::analysis
