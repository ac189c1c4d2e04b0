#include "analysis/simulation/random_motion.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>

#include <fftw3.h>

#include "analysis/common/input_error.h"
#include "analysis/signal/fftw_planner.h"

namespace oscilab::analysis {
namespace {

// Inverse real DFT without scaling: x[n] = Σ_k X[k] e^{2πikn/N} over the full Hermitian spectrum
// (FFTW's c2r convention, see docs/conventions.md).
std::vector<double> inverse_real_dft(std::vector<std::complex<double>> spectrum, std::size_t n) {
  std::vector<double> out(n);
  const std::lock_guard lock(fftw_planner_mutex());  // one-off transform: plan and run locked
  fftw_plan plan =
      fftw_plan_dft_c2r_1d(static_cast<int>(n), reinterpret_cast<fftw_complex*>(spectrum.data()),
                           out.data(), FFTW_ESTIMATE);
  fftw_execute(plan);
  fftw_destroy_plan(plan);
  return out;
}

double hermite(double y0, double y1, double m0, double m1, double s, double h) {
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * y0 + (s3 - 2 * s2 + s) * h * m0 + (-2 * s3 + 3 * s2) * y1 +
         (s3 - s2) * h * m1;
}

}  // namespace

RandomMotion::RandomMotion(const RandomMotionSpec& spec, double mass_kg) : spec_(spec) {
  if (!(spec.duration_s > 2 * spec.fade_s) || !(spec.fade_s > 0)) {
    throw InputError("random excitation: duration " + std::to_string(spec.duration_s) +
                     " s must exceed twice the fade of " + std::to_string(spec.fade_s) + " s");
  }
  if (!(spec.low_hz > 0) || !(spec.high_hz > spec.low_hz)) {
    throw InputError("random excitation: band " + std::to_string(spec.low_hz) + ":" +
                     std::to_string(spec.high_hz) + " Hz must satisfy 0 < low < high");
  }
  if (!(spec.force_rms_n >= 0) || !std::isfinite(spec.force_rms_n)) {
    throw InputError("random excitation: force rms must be a finite number >= 0");
  }
  if (!(mass_kg > 0)) throw InputError("random excitation: mass_kg must be positive");

  const double grid_rate_hz = std::max(4096.0, 64.0 * spec.high_hz);
  // The excitation is synthesised on one grid by inverse DFTs: about 100 B a grid point (four
  // spectra, four transforms, four interpolation tables), so 2^25 points (2.3 h at 4096 Hz) stay
  // near 3 GB. A longer or wider-band excitation is refused before anything is allocated.
  constexpr double kMaxGridPoints = 33554432.0;  // 2^25
  if (!(spec.duration_s * grid_rate_hz < kMaxGridPoints)) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "random excitation: duration %g s needs %.3g grid points at %g Hz, more than "
                  "the %.3g (%g s) it may hold",
                  spec.duration_s, spec.duration_s * grid_rate_hz, grid_rate_hz, kMaxGridPoints,
                  kMaxGridPoints / grid_rate_hz);
    throw InputError(text);
  }
  const auto n = static_cast<std::size_t>(std::ceil(spec.duration_s * grid_rate_hz)) + 1;
  grid_dt_s_ = 1.0 / grid_rate_hz;
  const double df = grid_rate_hz / static_cast<double>(n);

  // Band spectrum of b̈ with unit amplitude and random phases; b = B̈/(−ω²), ḃ = B̈/(iω),
  // b⃛ = iω B̈ (exact derivatives of the periodic band-limited signal).
  std::mt19937_64 rng(spec.seed);
  std::uniform_real_distribution<double> phase(0.0, 2.0 * std::numbers::pi);
  const std::size_t bins = n / 2 + 1;
  std::vector<std::complex<double>> acc(bins), vel(bins), disp(bins), jerk(bins);
  for (std::size_t k = 1; k < bins; ++k) {
    const double f = static_cast<double>(k) * df;
    if (f < spec.low_hz || f > spec.high_hz) continue;
    const double w = 2.0 * std::numbers::pi * f;
    const std::complex<double> a = std::polar(1.0, phase(rng));
    const std::complex<double> iw(0.0, w);
    acc[k] = a;
    vel[k] = a / iw;
    disp[k] = -a / (w * w);
    jerk[k] = a * iw;
  }
  std::vector<double> a = inverse_real_dft(acc, n), v = inverse_real_dft(vel, n),
                      x = inverse_real_dft(disp, n), j = inverse_real_dft(jerk, n);

  // Fade the displacement: b_w = w b, with w a C² ramp up and down, and its exact derivatives.
  b_.resize(n);
  b_dot_.resize(n);
  b_ddot_.resize(n);
  b_dddot_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * grid_dt_s_;
    const SmoothStep up = smooth_step(t / spec.fade_s);
    const SmoothStep down = smooth_step((spec.duration_s - t) / spec.fade_s);
    const double w = up.value * down.value;
    const double w1 = up.slope / spec.fade_s * down.value - up.value * down.slope / spec.fade_s;
    const double w2 = up.curvature / (spec.fade_s * spec.fade_s) * down.value -
                      2.0 * up.slope * down.slope / (spec.fade_s * spec.fade_s) +
                      up.value * down.curvature / (spec.fade_s * spec.fade_s);
    b_[i] = w * x[i];
    b_dot_[i] = w * v[i] + w1 * x[i];
    b_ddot_[i] = w * a[i] + 2.0 * w1 * v[i] + w2 * x[i];
    // The slope of b̈ for interpolation: the fade's third derivative is left out; it only acts
    // inside the fades, where it changes the interpolant by less than the Hermite error.
    b_dddot_[i] = w * j[i] + 3.0 * w1 * a[i] + 3.0 * w2 * v[i];
  }

  // Scale to the requested force rms over the unfaded middle.
  double sum2 = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * grid_dt_s_;
    if (t < spec.fade_s || t > spec.duration_s - spec.fade_s) continue;
    sum2 += b_ddot_[i] * b_ddot_[i];
    ++count;
  }
  const double rms_acc = count > 0 ? std::sqrt(sum2 / static_cast<double>(count)) : 0.0;
  const double gain = rms_acc > 0 ? spec.force_rms_n / (mass_kg * rms_acc) : 0.0;
  for (auto* series : {&b_, &b_dot_, &b_ddot_, &b_dddot_}) {
    for (double& value : *series) value *= gain;
  }
}

TableState RandomMotion::at(double t_s) const {
  if (!(t_s > 0.0) || t_s >= spec_.duration_s) return {};
  const double position = t_s / grid_dt_s_;
  const auto i = std::min(static_cast<std::size_t>(position), b_.size() - 2);
  const double s = position - static_cast<double>(i);
  const double h = grid_dt_s_;
  return {hermite(b_[i], b_[i + 1], b_dot_[i], b_dot_[i + 1], s, h),
          hermite(b_dot_[i], b_dot_[i + 1], b_ddot_[i], b_ddot_[i + 1], s, h),
          hermite(b_ddot_[i], b_ddot_[i + 1], b_dddot_[i], b_dddot_[i + 1], s, h)};
}

}  // namespace oscilab::analysis
