#include "analysis/signal/spectral_calculus.h"

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include <fftw3.h>

#include "analysis/common/input_error.h"
#include "analysis/signal/fft_size.h"

namespace oscilab::analysis {
namespace {

double raised_cosine(double s) {  // 0 at s ≤ 0, 1 at s ≥ 1
  if (s <= 0) return 0.0;
  if (s >= 1) return 1.0;
  return 0.5 - 0.5 * std::cos(std::numbers::pi * s);
}

}  // namespace

double spectral_window(double f_hz, const SpectralOptions& options, bool integrating) {
  double w = 1.0;
  if (f_hz == 0.0 && integrating) return 0.0;
  if (options.highpass_hz > 0)
    w *= raised_cosine((f_hz - options.highpass_hz) / options.highpass_hz);
  if (options.lowpass_hz > 0) {
    w *= 1.0 - raised_cosine((f_hz - options.lowpass_hz) / (0.25 * options.lowpass_hz));
  }
  return w;
}

Eigen::VectorXd spectral_derivative(const Eigen::VectorXd& x, double sample_rate_hz, int order,
                                    const SpectralOptions& options) {
  if (!(sample_rate_hz > 0)) throw InputError("spectral calculus: sample rate must be positive");
  const Eigen::Index n = x.size();
  if (n < 2) return Eigen::VectorXd::Zero(n);
  // Even extension x[0..n-1], x[n-1..0], continuous at the join, then padded with x[0] up to a
  // fast FFT size, so the periodic signal is continuous everywhere (only its slope may jump at
  // the record's ends: the filters ring there for ~1/lowpass_hz, see edge_trim_s).
  const auto m = static_cast<Eigen::Index>(fast_fft_size(static_cast<std::size_t>(2 * n)));
  std::vector<double> buffer(static_cast<std::size_t>(m), x[0]);
  for (Eigen::Index i = 0; i < n; ++i) {
    buffer[static_cast<std::size_t>(i)] = x[i];
    buffer[static_cast<std::size_t>(2 * n - 1 - i)] = x[i];
  }
  const Eigen::Index bins = m / 2 + 1;
  std::vector<std::complex<double>> spectrum(static_cast<std::size_t>(bins));
  fftw_plan forward =
      fftw_plan_dft_r2c_1d(static_cast<int>(m), buffer.data(),
                           reinterpret_cast<fftw_complex*>(spectrum.data()), FFTW_ESTIMATE);
  fftw_execute(forward);
  fftw_destroy_plan(forward);

  const double df = sample_rate_hz / static_cast<double>(m);
  const bool integrating = order < 0;
  for (Eigen::Index k = 0; k < bins; ++k) {
    const double f = static_cast<double>(k) * df;
    const double w = spectral_window(f, options, integrating);
    if (w == 0.0) {
      spectrum[static_cast<std::size_t>(k)] = 0.0;
      continue;
    }
    const std::complex<double> iw(0.0, 2.0 * std::numbers::pi * f);
    std::complex<double> factor = w / static_cast<double>(m);  // FFTW round trip scales by m
    for (int i = 0; i < std::abs(order); ++i) factor = order > 0 ? factor * iw : factor / iw;
    // The Nyquist bin of an even-length real signal is real; a derivative of odd order would
    // make it imaginary, which the c2r transform cannot represent: drop it.
    if (k == bins - 1 && m % 2 == 0 && std::abs(order) % 2 == 1) factor = 0.0;
    spectrum[static_cast<std::size_t>(k)] *= factor;
  }
  fftw_plan backward =
      fftw_plan_dft_c2r_1d(static_cast<int>(m), reinterpret_cast<fftw_complex*>(spectrum.data()),
                           buffer.data(), FFTW_ESTIMATE);
  fftw_execute(backward);
  fftw_destroy_plan(backward);
  Eigen::VectorXd out(n);
  for (Eigen::Index i = 0; i < n; ++i) out[i] = buffer[static_cast<std::size_t>(i)];
  return out;
}

}  // namespace oscilab::analysis
