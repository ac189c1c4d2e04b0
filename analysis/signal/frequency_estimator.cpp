#include "analysis/signal/frequency_estimator.h"

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "analysis/signal/fft_size.h"
#include "analysis/signal/fftw_planner.h"
#include "analysis/signal/real_fft.h"

namespace oscilab::analysis {

DominantTone dominant_tone(const Eigen::VectorXd& x, double sample_rate_hz, double min_hz) {
  DominantTone tone;
  const Eigen::Index n = x.size();
  if (n < 16 || !(sample_rate_hz > 0)) return tone;
  const double mean = x.mean();
  // Zero-padded to a fast FFT size: the Hann window already takes the record to zero at its ends.
  const auto n_fft = static_cast<Eigen::Index>(fast_fft_size(static_cast<std::size_t>(n)));
  FftwVector<double> buffer(static_cast<std::size_t>(n_fft), 0.0);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double hann = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * static_cast<double>(i) /
                                             static_cast<double>(n - 1));
    buffer[static_cast<std::size_t>(i)] = hann * (x[i] - mean);
  }
  const Eigen::Index bins = n_fft / 2 + 1;
  FftwVector<std::complex<double>> spectrum(static_cast<std::size_t>(bins));
  RealFft::of_size(static_cast<int>(n_fft)).forward(buffer.data(), spectrum.data());

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

  // Refine on the unwindowed record: |Σ x_n e^{−iωn/fs}| peaks exactly at the carrier of a
  // sine with a non-negative envelope (a stepped sine's envelope spectrum peaks at 0 Hz), where
  // the windowed interpolation above is biased by the envelope's sidebands. Golden-section
  // search over ±1 bin around the interpolated peak; the phasor is advanced by a recurrence.
  const auto magnitude = [&](double f_hz) {
    const std::complex<double> step =
        std::polar(1.0, -2.0 * std::numbers::pi * f_hz / sample_rate_hz);
    std::complex<double> phasor = 1.0, sum = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      sum += (x[i] - mean) * phasor;
      phasor *= step;
      if ((i & 1023) == 1023) phasor /= std::abs(phasor);  // keep |phasor| = 1 against rounding
    }
    return std::abs(sum);
  };
  const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
  double lo = tone.freq_hz - df, hi = tone.freq_hz + df;
  double x1 = hi - ratio * (hi - lo), x2 = lo + ratio * (hi - lo);
  double m1 = magnitude(x1), m2 = magnitude(x2);
  // The unwindowed peak's main lobe is 2/T wide: search down to 1e-4 of a bin.
  while (hi - lo > 1e-4 * df) {
    if (m1 > m2) {
      hi = x2;
      x2 = x1;
      m2 = m1;
      x1 = hi - ratio * (hi - lo);
      m1 = magnitude(x1);
    } else {
      lo = x1;
      x1 = x2;
      m1 = m2;
      x2 = lo + ratio * (hi - lo);
      m2 = magnitude(x2);
    }
  }
  tone.freq_hz = 0.5 * (lo + hi);
  double near = 0.0;
  for (Eigen::Index k = std::max<Eigen::Index>(1, peak - 4); k <= std::min(bins - 1, peak + 4);
       ++k) {
    near += power[static_cast<std::size_t>(k)];
  }
  tone.power_fraction = near / total;
  return tone;
}

}  // namespace oscilab::analysis
