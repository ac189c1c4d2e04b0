#include "analysis/signal/frequency_estimator.h"

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include <fftw3.h>

#include "analysis/signal/fft_size.h"

namespace oscilab::analysis {

DominantTone dominant_tone(const Eigen::VectorXd& x, double sample_rate_hz, double min_hz) {
  DominantTone tone;
  const Eigen::Index n = x.size();
  if (n < 16 || !(sample_rate_hz > 0)) return tone;
  const double mean = x.mean();
  // Zero-padded to a fast FFT size: the Hann window already takes the record to zero at its ends.
  const auto n_fft = static_cast<Eigen::Index>(fast_fft_size(static_cast<std::size_t>(n)));
  std::vector<double> buffer(static_cast<std::size_t>(n_fft), 0.0);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double hann = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * static_cast<double>(i) /
                                             static_cast<double>(n - 1));
    buffer[static_cast<std::size_t>(i)] = hann * (x[i] - mean);
  }
  const Eigen::Index bins = n_fft / 2 + 1;
  std::vector<std::complex<double>> spectrum(static_cast<std::size_t>(bins));
  fftw_plan plan =
      fftw_plan_dft_r2c_1d(static_cast<int>(n_fft), buffer.data(),
                           reinterpret_cast<fftw_complex*>(spectrum.data()), FFTW_ESTIMATE);
  fftw_execute(plan);
  fftw_destroy_plan(plan);

  const double df = sample_rate_hz / static_cast<double>(n_fft);
  const auto first = static_cast<Eigen::Index>(std::ceil(min_hz / df));
  Eigen::Index peak = -1;
  double peak_power = 0.0, total = 0.0;
  std::vector<double> power(static_cast<std::size_t>(bins));
  for (Eigen::Index k = 1; k < bins; ++k) {
    power[static_cast<std::size_t>(k)] = std::norm(spectrum[static_cast<std::size_t>(k)]);
    total += power[static_cast<std::size_t>(k)];
    if (k >= first && power[static_cast<std::size_t>(k)] > peak_power) {
      peak_power = power[static_cast<std::size_t>(k)];
      peak = k;
    }
  }
  if (peak <= 0 || peak >= bins - 1 || total <= 0) return tone;
  // Gaussian interpolation: ln|X| of a Hann-windowed tone is nearly parabolic around the peak.
  const double a = std::log(std::sqrt(power[static_cast<std::size_t>(peak - 1)]) + 1e-300);
  const double b = std::log(std::sqrt(power[static_cast<std::size_t>(peak)]) + 1e-300);
  const double c = std::log(std::sqrt(power[static_cast<std::size_t>(peak + 1)]) + 1e-300);
  const double denominator = a - 2 * b + c;
  const double offset = denominator != 0 ? 0.5 * (a - c) / denominator : 0.0;
  tone.freq_hz = (static_cast<double>(peak) + offset) * df;
  double near = 0.0;
  for (Eigen::Index k = std::max<Eigen::Index>(1, peak - 4); k <= std::min(bins - 1, peak + 4);
       ++k) {
    near += power[static_cast<std::size_t>(k)];
  }
  tone.power_fraction = near / total;
  return tone;
}

}  // namespace oscilab::analysis
