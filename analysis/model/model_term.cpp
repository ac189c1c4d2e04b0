#include "analysis/model/model_term.h"

#include <vector>

namespace oscilab::analysis {

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
