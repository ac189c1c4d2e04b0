#include "analysis/signal/streaming_integrator.h"

#include <cmath>
#include <complex>
#include <numbers>
#include <string>

#include "analysis/common/input_error.h"
#include "analysis/signal/fftw_planner.h"
#include "analysis/signal/real_fft.h"
#include "analysis/signal/spectral_calculus.h"

namespace oscilab::analysis {

StreamingIntegrator::StreamingIntegrator(const Options& options)
    : sample_rate_hz_(options.sample_rate_hz) {
  if (!(options.sample_rate_hz > 0) || !(options.latency_s > 0)) {
    throw InputError("streaming integrator: sample rate and latency must be positive");
  }
  if (options.order < 0 && !(options.highpass_hz > 0)) {
    throw InputError("streaming integrator: integrating needs a positive high-pass cut-off");
  }
  half_width_ = static_cast<int>(std::lround(options.latency_s * options.sample_rate_hz));
  if (half_width_ < 2) throw InputError("streaming integrator: latency below two samples");
  const int taps = 2 * half_width_ + 1;

  // Impulse response of W(f)(i2πf)^order by an inverse DFT on a grid much longer than the
  // filter (8×, so the periodic wrap-around of the sampled response is negligible), centred,
  // truncated to ±K and tapered.
  const int grid = 8 * taps;
  FftwVector<std::complex<double>> response(static_cast<std::size_t>(grid / 2 + 1));
  SpectralOptions band;
  band.highpass_hz = options.highpass_hz;
  band.lowpass_hz = options.lowpass_hz;
  const double df = options.sample_rate_hz / grid;
  for (std::size_t k = 0; k < response.size(); ++k) {
    const double f = static_cast<double>(k) * df;
    const double w = spectral_window(f, band, options.order < 0);
    if (w == 0.0) continue;
    if (k + 1 == response.size() && std::abs(options.order) % 2 == 1) continue;  // Nyquist bin
    std::complex<double> value = w;
    const std::complex<double> iw(0.0, 2.0 * std::numbers::pi * f);
    for (int i = 0; i < std::abs(options.order); ++i)
      value = options.order > 0 ? value * iw : value / iw;
    response[k] = value / static_cast<double>(grid);
  }
  FftwVector<double> impulse(static_cast<std::size_t>(grid));
  RealFft::of_size(grid).inverse(response.data(), impulse.data());
  taps_.resize(static_cast<std::size_t>(taps));
  for (int j = -half_width_; j <= half_width_; ++j) {
    // Tukey taper: flat over the inner half, raised-cosine to zero over the outer quarters, so
    // the response's core (|t| ≲ K/2, where the high-pass's ringing lives) is kept unweighted.
    const double u = std::abs(static_cast<double>(j)) / half_width_;  // 0 at centre, 1 at ends
    const double taper = u <= 0.5 ? 1.0 : 0.5 + 0.5 * std::cos(std::numbers::pi * (u - 0.5) / 0.5);
    const double h = impulse[static_cast<std::size_t>((j + grid) % grid)];
    // y(t − K) = Σ_j h[j] x(t − K − j): tap index for input x(t − m) is m = K + j.
    taps_[static_cast<std::size_t>(half_width_ + j)] = taper * h;
  }
  history_.assign(2 * taps_.size(), 0.0);
}

double StreamingIntegrator::push(double x) {
  const std::size_t n = taps_.size();
  // Write each sample twice (at head and head + n) so the last n inputs are always contiguous.
  head_ = head_ == 0 ? n - 1 : head_ - 1;
  history_[head_] = x;
  history_[head_ + n] = x;
  ++pushed_;
  const double* recent = history_.data() + head_;  // recent[m] = x(t − m)
  double y = 0.0;
  for (std::size_t m = 0; m < n; ++m) y += taps_[m] * recent[m];
  return y;
}

}  // namespace oscilab::analysis
