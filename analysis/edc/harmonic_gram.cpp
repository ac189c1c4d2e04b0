#include "analysis/edc/harmonic_gram.h"

#include <cmath>
#include <complex>
#include <cstdlib>
#include <numbers>
#include <vector>

namespace oscilab::analysis {

bool harmonic_gram_evenly_spaced(int n, double theta0_rad, double dtheta_rad, double tau0_s,
                                 double dt_s, int harmonics, Eigen::MatrixXd& gram) {
  const int orders = 2 * harmonics;  // sums of cos kθ and sin kθ are needed up to k = 2H
  const double count = n;
  const double middle = 0.5 * (count - 1.0);
  const double theta_c = theta0_rad + middle * dtheta_rad;
  const double tau_c = tau0_s + middle * dt_s;

  // sin and cos of k Δθ/2, of k n Δθ/2 and e^{ikθ_c} for k = 0..2H, each by the angle-addition
  // recurrence from one sincos (rounding grows as k ε, at most 16 ε here).
  const std::complex<double> half_step = std::polar(1.0, 0.5 * dtheta_rad);
  const std::complex<double> n_half_step = std::polar(1.0, 0.5 * count * dtheta_rad);
  const std::complex<double> centre = std::polar(1.0, theta_c);
  std::complex<double> half = 1.0, n_half = 1.0, phase = 1.0;
  // P_k = Σ_j e^{ikθ_j} (k ≤ 2H) and T_k = Σ_j τ_j e^{ikθ_j} (1 ≤ k ≤ H).
  thread_local std::vector<std::complex<double>> sums, weighted;
  sums.assign(static_cast<std::size_t>(orders + 1), 0.0);
  weighted.assign(static_cast<std::size_t>(harmonics + 1), 0.0);
  sums[0] = count;
  for (int k = 1; k <= orders; ++k) {
    half *= half_step;
    n_half *= n_half_step;
    phase *= centre;
    const double s = half.imag();
    // Near kΔθ/2 = mπ with m ≥ 1 the sine's relative error is about ε (kΔθ/2) / |sin|; below
    // π/2 it stays ε (a small kΔθ is itself accurate).
    if (0.5 * k * dtheta_rad > 0.5 * std::numbers::pi && std::abs(s) < kMinHalfAngleSine) {
      return false;
    }
    const double dirichlet = n_half.imag() / s;  // D(kΔθ)
    sums[static_cast<std::size_t>(k)] = phase * dirichlet;
    if (k <= harmonics) {
      // G(x) = −D'(x) = (sin(nx/2) cos(x/2) − n cos(nx/2) sin(x/2)) / (2 sin²(x/2)).
      const double g = (n_half.imag() * half.real() - count * n_half.real() * s) / (2.0 * s * s);
      weighted[static_cast<std::size_t>(k)] =
          tau_c * sums[static_cast<std::size_t>(k)] + dt_s * std::complex<double>(0.0, g) * phase;
    }
  }
  const auto cos_sum = [&](int k) { return sums[static_cast<std::size_t>(std::abs(k))].real(); };
  const auto sin_sum = [&](int k) {  // S(−k) = −S(k)
    const double s = sums[static_cast<std::size_t>(std::abs(k))].imag();
    return k < 0 ? -s : s;
  };

  const int columns = 2 + 2 * harmonics;
  gram.resize(columns, columns);
  gram(0, 0) = count;
  gram(1, 0) = count * tau_c;
  gram(1, 1) = count * tau_c * tau_c + dt_s * dt_s * count * (count * count - 1.0) / 12.0;
  for (int h = 1; h <= harmonics; ++h) {
    const int c = 2 * h, s = 2 * h + 1;  // the columns cos hθ and −sin hθ
    gram(c, 0) = cos_sum(h);
    gram(s, 0) = -sin_sum(h);
    gram(c, 1) = weighted[static_cast<std::size_t>(h)].real();
    gram(s, 1) = -weighted[static_cast<std::size_t>(h)].imag();
    for (int g = 1; g <= h; ++g) {
      const int cg = 2 * g, sg = 2 * g + 1;
      // cos h cos g = (cos(h−g) + cos(h+g))/2, sin h sin g = (cos(h−g) − cos(h+g))/2,
      // sin g cos h = (sin(g+h) + sin(g−h))/2.
      gram(c, cg) = 0.5 * (cos_sum(h - g) + cos_sum(h + g));
      gram(s, sg) = 0.5 * (cos_sum(h - g) - cos_sum(h + g));
      gram(c, sg) = -0.5 * (sin_sum(g + h) + sin_sum(g - h));
      gram(s, cg) = -0.5 * (sin_sum(h + g) + sin_sum(h - g));
    }
  }
  gram.triangularView<Eigen::StrictlyUpper>() = gram.transpose();
  return true;
}

}  // namespace oscilab::analysis
