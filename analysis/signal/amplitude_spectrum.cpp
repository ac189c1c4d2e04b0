#include "analysis/signal/amplitude_spectrum.h"

#include <cmath>
#include <complex>
#include <numbers>

#include "analysis/signal/fft_size.h"
#include "analysis/signal/fftw_planner.h"
#include "analysis/signal/real_fft.h"

namespace oscilab::analysis {
namespace {

constexpr std::size_t kMinSpectrumSamples = 64;

}  // namespace

ZSpectrum z_spectrum(const std::vector<double>& z_m, double sample_rate_hz, double frequency_hz,
                     int harmonics) {
  ZSpectrum out;
  if (!(sample_rate_hz > 0)) return out;
  std::size_t end = z_m.size();
  while (end > 0 && !std::isfinite(z_m[end - 1])) --end;
  std::size_t begin = end;
  while (begin > 0 && std::isfinite(z_m[begin - 1])) --begin;
  const std::size_t n = end - begin;
  if (n < kMinSpectrumSamples) return out;
  out.duration_s = static_cast<double>(n) / sample_rate_hz;

  double mean = 0.0;
  for (std::size_t i = begin; i < end; ++i) mean += z_m[i];
  mean /= static_cast<double>(n);
  // Periodic Hann window: coherent gain Σw = n/2, so a sine of amplitude A at a bin reads
  // A = 2 |X| / Σw (docs/conventions.md, one-sided amplitudes, with the window's gain).
  FftwVector<double> x(fast_fft_size(n), 0.0);
  double gain = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double w =
        0.5 *
        (1.0 - std::cos(2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n)));
    x[i] = w * (z_m[begin + i] - mean);
    gain += w;
  }
  const int size = static_cast<int>(x.size());
  FftwVector<std::complex<double>> spectrum(x.size() / 2 + 1);
  RealFft::of_size(size).forward(x.data(), spectrum.data());
  out.freq_hz.resize(spectrum.size());
  out.amplitude_m.resize(spectrum.size());
  for (std::size_t k = 0; k < spectrum.size(); ++k) {
    out.freq_hz[k] = static_cast<double>(k) * sample_rate_hz / size;
    out.amplitude_m[k] = (k == 0 ? 1.0 : 2.0) * std::abs(spectrum[k]) / gain;
  }
  // The DFT of the windowed samples at exactly f.
  const auto amplitude_at = [&](double f_hz) {
    std::complex<double> sum = 0.0;
    const double step = -2.0 * std::numbers::pi * f_hz / sample_rate_hz;
    for (std::size_t i = 0; i < n; ++i)
      sum += x[i] * std::polar(1.0, step * static_cast<double>(i));
    return 2.0 * std::abs(sum) / gain;
  };
  if (frequency_hz > 0) {
    for (int h = 1; h <= harmonics && h * frequency_hz < 0.5 * sample_rate_hz; ++h) {
      out.harmonic_freq_hz.push_back(h * frequency_hz);
      out.harmonic_amplitude_m.push_back(amplitude_at(h * frequency_hz));
    }
    out.subharmonic_amplitude_m = amplitude_at(0.5 * frequency_hz);
  }
  return out;
}

}  // namespace oscilab::analysis
