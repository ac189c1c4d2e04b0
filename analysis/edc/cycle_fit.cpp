#include "analysis/edc/cycle_fit.h"
#include "analysis/edc/harmonic_gram.h"
#include "analysis/model/excitation_force.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Cholesky>

namespace oscilab::analysis {
namespace {

// Displacement phasor of a harmonic measured as a derivative of order `order`: X / (ihω)^order.
std::complex<double> to_displacement(std::complex<double> x, double h_omega, int order) {
  const std::complex<double> iw(0.0, h_omega);
  for (int i = 0; i < order; ++i) x /= iw;
  return x;
}

// Whether t[j] = t[0] + j dt for j < n, to 1e-7 dt: a recording's timestamps j / rate are, to
// rounding, for records up to 10⁹ samples. Taken as even, a sample's phase at order k is off by
// at most 1e-7 kΔθ (Δθ = ω dt), far below what a cycle's fit resolves.
bool evenly_spaced(const double* t, int n, double dt) {
  if (!(dt > 0)) return false;
  const double tolerance = 1e-7 * dt;
  for (int j = 1; j < n - 1; ++j) {
    if (std::abs(t[j] - (t[0] + j * dt)) > tolerance) return false;
  }
  return true;
}

// One cycle's samples: [first, last) inside [start_s, end_s), and lo..hi with one neighbour on
// each side (for the trapezoid's partial intervals); the basis has rows lo..hi.
struct CycleWindow {
  double period = 0.0, omega = 0.0, start_s = 0.0, end_s = 0.0, t_mid = 0.0;
  int first = 0, last = 0, n = 0, lo = 0, hi = 0, rows = 0;
  double dt = 0.0;  // mean sample interval over lo..hi
  bool even = false;
};

// Basis rows for the samples lo..hi. Columns: 1, t − t_mid, then cos(hωτ), −sin(hωτ) for
// h = 1..H, τ = t − t_ref, by the angle-addition recurrence from e^{iωτ}. That is one sincos
// per sample, or for evenly spaced samples one per cycle, advanced by e^{iω dt} from sample to
// sample (rounding grows as the row count times ε: 1e-13 at 0.1 Hz and 10 kHz).
Eigen::MatrixXd harmonic_basis(const CycleWindow& w, const double* t_s, double t_ref_s,
                               int harmonics) {
  const std::complex<double> step = std::polar(1.0, w.omega * w.dt);
  std::complex<double> phasor = std::polar(1.0, w.omega * (t_s[w.lo] - t_ref_s));
  Eigen::MatrixXd basis(w.rows, 2 + 2 * harmonics);
  for (int r = 0; r < w.rows; ++r) {
    const double t = t_s[w.lo + r];
    if (!w.even && r > 0) phasor = std::polar(1.0, w.omega * (t - t_ref_s));
    const double c1 = phasor.real(), s1 = phasor.imag();
    if (w.even) phasor *= step;
    basis(r, 0) = 1.0;
    basis(r, 1) = t - w.t_mid;
    double c = c1, sn = s1;
    for (int h = 1; h <= harmonics; ++h) {
      basis(r, 2 * h) = c;
      basis(r, 2 * h + 1) = -sn;
      const double next_c = c * c1 - sn * s1;
      sn = sn * c1 + c * s1;
      c = next_c;
    }
  }
  return basis;
}

// Least squares of both channels on the window's rows by the normal equations: over one period
// the columns are close to orthogonal (sines and cosines of whole harmonics, a centred linear
// term), so AᵀA is well conditioned and its Cholesky factor is as accurate as a QR here, at a
// quarter of the cost. The channels are offset by their first sample so that the sums carry no
// large constant. Sets the residuals' rms in `out`; false when AᵀA is not positive definite.
bool fit_coefficients(const CycleWindow& w, const Eigen::MatrixXd& basis, const double* t_s,
                      const double* base, const double* mass, double t_ref_s, int harmonics,
                      Eigen::MatrixXd& coefficients, CycleFit& out) {
  const int n = w.n, first = w.first, columns = static_cast<int>(basis.cols());
  const auto window = basis.middleRows(first - w.lo, n);
  Eigen::MatrixXd values(n, 2);
  const double base_offset = base[first], mass_offset = mass[first];
  for (int r = 0; r < n; ++r) {
    values(r, 0) = base[first + r] - base_offset;
    values(r, 1) = mass[first + r] - mass_offset;
  }
  // AᵀA's lower triangle (all LLT reads) and Aᵀv as dot products of the basis columns: half the
  // products of a general AᵀA, and at these sizes (some 60 × 18) without a general product's
  // packing and blocking (6 % less time for the whole EDC path, BM_OfflineEdc).
  // Evenly spaced samples (a recording's, a gap-free stream's) give AᵀA in closed form
  // (harmonic_gram.h), otherwise it is summed.
  Eigen::MatrixXd gram;
  if (!w.even || !harmonic_gram_evenly_spaced(n, w.omega * (t_s[first] - t_ref_s), w.omega * w.dt,
                                              t_s[first] - w.t_mid, w.dt, harmonics, gram)) {
    gram.resize(columns, columns);
    for (int c = 0; c < columns; ++c) {
      for (int r = c; r < columns; ++r) gram(r, c) = window.col(r).dot(window.col(c));
    }
  }
  Eigen::MatrixXd projections(columns, 2);
  for (int c = 0; c < columns; ++c) {
    projections(c, 0) = window.col(c).dot(values.col(0));
    projections(c, 1) = window.col(c).dot(values.col(1));
  }
  const Eigen::LLT<Eigen::MatrixXd, Eigen::Lower> cholesky(gram);
  if (cholesky.info() != Eigen::Success) return false;
  // Column by column: a vector's triangular solves, not the blocked matrix kernels that a
  // two-column right-hand side takes (and that cost more at this size).
  coefficients.resize(columns, 2);
  coefficients.col(0) = cholesky.solve(projections.col(0));
  coefficients.col(1) = cholesky.solve(projections.col(1));
  const Eigen::MatrixXd residual = window.lazyProduct(coefficients) - values;
  coefficients(0, 0) += base_offset;
  coefficients(0, 1) += mass_offset;
  // Residual rms with the degrees of freedom of the fit removed (unbiased for white noise).
  const double dof = std::max(1, n - columns);
  out.base_residual_rms = std::sqrt(residual.col(0).squaredNorm() / dof);
  out.mass_residual_rms = std::sqrt(residual.col(1).squaredNorm() / dof);
  return true;
}

// The harmonics as displacement phasors, the basis's coefficient vectors of b and z and of the
// table's acceleration −(hω)² B_h (for the force).
struct HarmonicDisplacements {
  Eigen::VectorXd b_disp, z_disp, b_acc;
};

// Harmonic coefficients as displacement: X / (ihω)^order, with X = a + ib for the basis columns
// (cos, −sin). Sets z_h, y1_abs_m, the EDC by Parseval and by eq. (13), f0 and the lag.
HarmonicDisplacements harmonic_phasors(const CycleFitInput& input, const CycleWindow& w,
                                       const Eigen::MatrixXd& coefficients, int harmonics,
                                       CycleFit& out) {
  const int base_order = derivative_order(input.base_quantity);
  const int mass_order = derivative_order(input.mass_quantity);
  const Eigen::Index columns = coefficients.rows();
  HarmonicDisplacements d{Eigen::VectorXd::Zero(columns), Eigen::VectorXd::Zero(columns),
                          Eigen::VectorXd::Zero(columns)};
  out.z_h.assign(static_cast<std::size_t>(harmonics), {});
  std::vector<std::complex<double>> f_h(static_cast<std::size_t>(harmonics));
  double edc = 0.0;
  for (int h = 1; h <= harmonics; ++h) {
    const double hw = h * w.omega;
    const std::complex<double> b(coefficients(2 * h, 0), coefficients(2 * h + 1, 0));
    const std::complex<double> y(coefficients(2 * h, 1), coefficients(2 * h + 1, 1));
    const std::complex<double> b_d = to_displacement(b, hw, base_order);
    const std::complex<double> y_d = to_displacement(y, hw, mass_order);
    const std::complex<double> z = input.mass_is_relative ? y_d : y_d - b_d;
    const std::complex<double> f = excitation_force_harmonic(input.mass_kg, hw, b_d);
    out.z_h[static_cast<std::size_t>(h - 1)] = z;
    if (h == 1) out.y1_abs_m = std::abs(y_d);
    f_h[static_cast<std::size_t>(h - 1)] = f;
    d.b_disp(2 * h) = b_d.real();
    d.b_disp(2 * h + 1) = b_d.imag();
    d.z_disp(2 * h) = z.real();
    d.z_disp(2 * h + 1) = z.imag();
    d.b_acc(2 * h) = -hw * hw * b_d.real();
    d.b_acc(2 * h + 1) = -hw * hw * b_d.imag();
    // Parseval: ∫_T f ż dt = (T/2) Σ_h hω Im(F_h conj Z_h).
    edc += 0.5 * w.period * hw * std::imag(f * std::conj(z));
  }
  out.edc_j = edc;

  // Eq. (13) with the lag θ1 of z behind f: S₁ = (T/2) ω Im(F1 conj Z1) = π |F1| |Z1| sin θ1.
  const std::complex<double> f1 = f_h[0], z1 = out.z_h[0];
  out.f0_n = std::abs(f1);
  out.lag_rad = std::remainder(std::arg(f1) - std::arg(z1), 2.0 * std::numbers::pi);
  out.edc_eq13_j = std::numbers::pi * out.f0_n * std::abs(z1) * std::sin(out.lag_rad);
  return d;
}

// Trapezoidal ∮ f dz over the samples, with the measured force where the base channel is an
// acceleration (f = −m b̈) and z = y − b_fit where the mass channel is a displacement;
// otherwise the fitted signal stands in (`z_fit`, `b_fit`: the harmonic parts at lo..hi).
// Partial intervals at the window edges are interpolated linearly between the samples outside
// and inside.
double trapezoid_edc(const CycleFitInput& input, const CycleWindow& w, const Eigen::MatrixXd& basis,
                     const HarmonicDisplacements& d, const Eigen::VectorXd& z_fit,
                     const Eigen::VectorXd& b_fit, const double* t_s, const double* base,
                     const double* mass) {
  const int base_order = derivative_order(input.base_quantity);
  const int mass_order = derivative_order(input.mass_quantity);
  const int lo = w.lo;
  const Eigen::VectorXd b_acc_fit =
      base_order == 2 ? Eigen::VectorXd() : Eigen::VectorXd(basis.lazyProduct(d.b_acc));
  const auto force_at = [&](int i) {
    return excitation_force_n(input.mass_kg, base_order == 2 ? base[i] : b_acc_fit[i - lo]);
  };
  const auto z_at = [&](int i) {
    if (mass_order != 0) return z_fit[i - lo];
    return input.mass_is_relative ? mass[i] : mass[i] - b_fit[i - lo];
  };
  double area = 0.0;
  const auto lerp = [](double a, double b, double s) { return a + (b - a) * s; };
  for (int i = lo; i < w.hi; ++i) {
    double ta = t_s[i], tb = t_s[i + 1];
    double fa = force_at(i), fb = force_at(i + 1), za = z_at(i), zb = z_at(i + 1);
    if (ta < w.start_s) {
      const double s = (w.start_s - ta) / (tb - ta);
      fa = lerp(fa, fb, s);
      za = lerp(za, zb, s);
      ta = w.start_s;
    }
    if (tb > w.end_s) {
      const double s = (w.end_s - ta) / (tb - ta);
      fb = lerp(fa, fb, s);
      zb = lerp(za, zb, s);
      tb = w.end_s;
    }
    if (tb > ta) area += 0.5 * (fa + fb) * (zb - za);
  }
  return area;
}

}  // namespace

bool fit_cycle(const CycleFitInput& input, double start_s, const double* t_s, const double* base,
               const double* mass, int count, CycleFit& out) {
  CycleWindow w;
  w.period = 1.0 / input.freq_hz;
  w.start_s = start_s;
  w.end_s = start_s + w.period;
  w.omega = 2.0 * std::numbers::pi * input.freq_hz;
  while (w.first < count && t_s[w.first] < start_s) ++w.first;
  w.last = w.first;  // one past the last sample inside the window
  while (w.last < count && t_s[w.last] < w.end_s) ++w.last;
  w.n = w.last - w.first;
  const int harmonics = std::min(input.harmonics, (w.n - 3) / 2);
  if (harmonics < 1 || w.n < input.min_samples) return false;
  w.lo = std::max(0, w.first - 1);
  w.hi = std::min(count - 1, w.last);
  w.rows = w.hi - w.lo + 1;
  w.t_mid = start_s + 0.5 * w.period;
  w.dt = (t_s[w.hi] - t_s[w.lo]) / (w.rows - 1);
  w.even = evenly_spaced(t_s + w.lo, w.rows, w.dt);

  const Eigen::MatrixXd basis = harmonic_basis(w, t_s, input.t_ref_s, harmonics);
  Eigen::MatrixXd coefficients;
  if (!fit_coefficients(w, basis, t_s, base, mass, input.t_ref_s, harmonics, coefficients, out)) {
    return false;
  }
  out.start_s = start_s;
  out.end_s = w.end_s;
  out.samples = w.n;
  const HarmonicDisplacements d = harmonic_phasors(input, w, coefficients, harmonics, out);

  // Mean and extremes of z over the cycle from the fit, at the sample times (the constant of a
  // velocity or acceleration channel is not a position: then only a displacement sets the mean).
  const int base_order = derivative_order(input.base_quantity);
  const int mass_order = derivative_order(input.mass_quantity);
  const double y_mean = mass_order == 0 ? coefficients(0, 1) : 0.0;
  const double b_mean = base_order == 0 ? coefficients(0, 0) : 0.0;
  out.z_mean_m = input.mass_is_relative ? y_mean : y_mean - b_mean;
  const Eigen::VectorXd z_fit = basis.lazyProduct(d.z_disp);  // harmonic part at lo..hi
  const Eigen::VectorXd b_fit = basis.lazyProduct(d.b_disp);
  out.z_min_m = out.z_mean_m + z_fit.segment(w.first - w.lo, w.n).minCoeff();
  out.z_max_m = out.z_mean_m + z_fit.segment(w.first - w.lo, w.n).maxCoeff();
  out.edc_trapz_j = trapezoid_edc(input, w, basis, d, z_fit, b_fit, t_s, base, mass);
  return true;
}

}  // namespace oscilab::analysis
