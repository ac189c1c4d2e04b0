#include "analysis/edc/cycle_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/QR>

namespace oscilab::analysis {
namespace {

// Displacement phasor of a harmonic measured as a derivative of order `order`: X / (ihω)^order.
std::complex<double> to_displacement(std::complex<double> x, double h_omega, int order) {
  const std::complex<double> iw(0.0, h_omega);
  for (int i = 0; i < order; ++i) x /= iw;
  return x;
}

}  // namespace

bool fit_cycle(const CycleFitInput& input, double start_s, const double* t_s, const double* base,
               const double* mass, int count, CycleFit& out) {
  const double period = 1.0 / input.freq_hz;
  const double end_s = start_s + period;
  const double omega = 2.0 * std::numbers::pi * input.freq_hz;
  int first = 0;
  while (first < count && t_s[first] < start_s) ++first;
  int last = first;  // one past the last sample inside the window
  while (last < count && t_s[last] < end_s) ++last;
  const int n = last - first;
  const int harmonics = std::min(input.harmonics, (n - 3) / 2);
  if (harmonics < 1 || n < input.min_samples) return false;

  const int columns = 2 + 2 * harmonics;
  const double t_mid = start_s + 0.5 * period;
  Eigen::MatrixXd design(n, columns);
  Eigen::MatrixXd rhs(n, 2);
  for (int r = 0; r < n; ++r) {
    const double t = t_s[first + r];
    design(r, 0) = 1.0;
    design(r, 1) = t - t_mid;
    for (int h = 1; h <= harmonics; ++h) {
      const double phase = h * omega * (t - input.t_ref_s);
      design(r, 2 * h) = std::cos(phase);
      design(r, 2 * h + 1) = -std::sin(phase);
    }
    rhs(r, 0) = base[first + r];
    rhs(r, 1) = mass[first + r];
  }
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(design);
  const Eigen::MatrixXd coefficients = qr.solve(rhs);
  const Eigen::MatrixXd residual = design * coefficients - rhs;
  // Residual rms with the degrees of freedom of the fit removed (unbiased for white noise).
  const double dof = std::max(1, n - columns);
  out.base_residual_rms = std::sqrt(residual.col(0).squaredNorm() / dof);
  out.mass_residual_rms = std::sqrt(residual.col(1).squaredNorm() / dof);

  const int base_order = derivative_order(input.base_quantity);
  const int mass_order = derivative_order(input.mass_quantity);
  out.start_s = start_s;
  out.end_s = end_s;
  out.samples = n;
  out.z_h.assign(static_cast<std::size_t>(harmonics), {});
  std::vector<std::complex<double>> f_h(static_cast<std::size_t>(harmonics));
  double edc = 0.0;
  for (int h = 1; h <= harmonics; ++h) {
    const double hw = h * omega;
    const std::complex<double> b(coefficients(2 * h, 0), coefficients(2 * h + 1, 0));
    const std::complex<double> y(coefficients(2 * h, 1), coefficients(2 * h + 1, 1));
    const std::complex<double> b_disp = to_displacement(b, hw, base_order);
    const std::complex<double> y_disp = to_displacement(y, hw, mass_order);
    const std::complex<double> z = input.mass_is_relative ? y_disp : y_disp - b_disp;
    const std::complex<double> f = input.mass_kg * hw * hw * b_disp;  // F_h = −m (ihω)² B_h
    out.z_h[static_cast<std::size_t>(h - 1)] = z;
    f_h[static_cast<std::size_t>(h - 1)] = f;
    edc += 0.5 * period * hw * std::imag(f * std::conj(z));
  }
  out.edc_j = edc;

  // Eq. (13) with the lag θ1 of z behind f: S₁ = (T/2) ω Im(F1 conj Z1) = π |F1| |Z1| sin θ1.
  const std::complex<double> f1 = f_h[0], z1 = out.z_h[0];
  out.f0_n = std::abs(f1);
  out.lag_rad = std::arg(f1) - std::arg(z1);
  out.lag_rad = std::remainder(out.lag_rad, 2.0 * std::numbers::pi);
  out.edc_eq13_j = std::numbers::pi * out.f0_n * std::abs(z1) * std::sin(out.lag_rad);

  // Mean and extremes of z over the cycle from the fit (the constant of a velocity or
  // acceleration channel is not a position: then only a displacement channel sets the mean).
  const double y_mean = mass_order == 0 ? coefficients(0, 1) : 0.0;
  const double b_mean = base_order == 0 ? coefficients(0, 0) : 0.0;
  out.z_mean_m = input.mass_is_relative ? y_mean : y_mean - b_mean;
  out.z_min_m = std::numeric_limits<double>::infinity();
  out.z_max_m = -out.z_min_m;
  constexpr int kEvaluations = 64;
  for (int k = 0; k < kEvaluations; ++k) {
    const double t = start_s + period * k / kEvaluations;
    double z = out.z_mean_m;
    for (int h = 1; h <= harmonics; ++h) {
      z += std::real(out.z_h[static_cast<std::size_t>(h - 1)] *
                     std::polar(1.0, h * omega * (t - input.t_ref_s)));
    }
    out.z_min_m = std::min(out.z_min_m, z);
    out.z_max_m = std::max(out.z_max_m, z);
  }

  // Trapezoidal ∮ f dz over the samples, with the measured force where the base channel is an
  // acceleration (f = −m b̈) and z = y − b_fit where the mass channel is a displacement;
  // otherwise the fitted signal stands in. Partial intervals at the window edges are
  // interpolated linearly between the samples outside and inside.
  std::vector<std::complex<double>> b_h(static_cast<std::size_t>(harmonics));
  for (int h = 1; h <= harmonics; ++h) {
    const std::complex<double> bh(coefficients(2 * h, 0), coefficients(2 * h + 1, 0));
    b_h[static_cast<std::size_t>(h - 1)] = to_displacement(bh, h * omega, base_order);
  }
  // Σ_h Re((ihω)^order X_h e^{ihω(t − t_ref)}) for displacement phasors X_h.
  const auto synthesise = [&](const std::vector<std::complex<double>>& x, int order, double t) {
    double value = 0.0;
    for (int h = 1; h <= harmonics; ++h) {
      const double hw = h * omega;
      value +=
          std::real(std::pow(std::complex<double>(0.0, hw), order) *
                    x[static_cast<std::size_t>(h - 1)] * std::polar(1.0, hw * (t - input.t_ref_s)));
    }
    return value;
  };
  const auto force_at = [&](int i) {
    const double b_ddot = base_order == 2 ? base[i] : synthesise(b_h, 2, t_s[i]);
    return -input.mass_kg * b_ddot;
  };
  const auto z_at = [&](int i) {
    if (mass_order != 0) return synthesise(out.z_h, 0, t_s[i]);
    return input.mass_is_relative ? mass[i] : mass[i] - synthesise(b_h, 0, t_s[i]);
  };
  double area = 0.0;
  const int lo = std::max(0, first - 1), hi = std::min(count - 1, last);
  for (int i = lo; i < hi; ++i) {
    double ta = t_s[i], tb = t_s[i + 1];
    double fa = force_at(i), fb = force_at(i + 1), za = z_at(i), zb = z_at(i + 1);
    // Clip the interval to the window by linear interpolation.
    const auto lerp = [](double a, double b, double s) { return a + (b - a) * s; };
    if (ta < start_s) {
      const double s = (start_s - ta) / (tb - ta);
      fa = lerp(fa, fb, s);
      za = lerp(za, zb, s);
      ta = start_s;
    }
    if (tb > end_s) {
      const double s = (end_s - ta) / (tb - ta);
      fb = lerp(fa, fb, s);
      zb = lerp(za, zb, s);
      tb = end_s;
    }
    if (tb > ta) area += 0.5 * (fa + fb) * (zb - za);
  }
  out.edc_trapz_j = area;
  return true;
}

}  // namespace oscilab::analysis
