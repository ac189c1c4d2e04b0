#include "analysis/signal/spectral_calculus.h"

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "analysis/common/input_error.h"
#include "analysis/signal/fft_size.h"
#include "analysis/signal/real_fft.h"

namespace oscilab::analysis {
namespace {

double raised_cosine(double s) {  // 0 at s ≤ 0, 1 at s ≥ 1
  if (s <= 0) return 0.0;
  if (s >= 1) return 1.0;
  return 0.5 - 0.5 * std::cos(std::numbers::pi * s);
}

// The transforms' full-length real arrays (the even extension going in, the inverse's output
// coming out) are scratch, one per thread for both: a fresh multi-megabyte buffer per call costs
// more in page faults than the transform itself (measured: 11 ms of first-touch faults against
// 2 ms of FFT for 270000 points on the 2-core CI machine).
FftwVector<double>& scratch_samples() {
  thread_local FftwVector<double> buffer;
  return buffer;
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

SpectralRecord::SpectralRecord(const Eigen::VectorXd& x, double sample_rate_hz)
    : n_(x.size()), sample_rate_hz_(sample_rate_hz) {
  if (!(sample_rate_hz > 0)) throw InputError("spectral calculus: sample rate must be positive");
  if (n_ < 2) throw InputError("spectral calculus: a record needs at least two samples");
  // Even extension x[0..n-1], x[n-1..0], continuous at the join, then padded with x[0] up to a
  // fast FFT size, so the periodic signal is continuous everywhere (only its slope may jump at
  // the record's ends: the filters ring there, see PipelineSettings::edge_trim_s).
  size_ = static_cast<Eigen::Index>(fast_fft_size(static_cast<std::size_t>(2 * n_)));
  bins_ = size_ / 2 + 1;
  FftwVector<double>& buffer = scratch_samples();
  buffer.assign(static_cast<std::size_t>(size_), x[0]);
  for (Eigen::Index i = 0; i < n_; ++i) {
    buffer[static_cast<std::size_t>(i)] = x[i];
    buffer[static_cast<std::size_t>(2 * n_ - 1 - i)] = x[i];
  }
  spectrum_.resize(static_cast<std::size_t>(bins_));
  transform_ = &RealFft::of_size(static_cast<int>(size_));
  transform_->forward(buffer.data(), spectrum_.data());
}

void SpectralRecord::accumulate(Spectrum& spectrum, double gain, int order,
                                const SpectralOptions& options) const {
  const double df = sample_rate_hz_ / static_cast<double>(size_);
  const bool integrating = order < 0;
  const double scale = gain / static_cast<double>(size_);  // FFTW's round trip multiplies by size
  // (iω)^order = ω^order i^order: a real factor and |order| quarter turns (i^−1 = −i).
  const int quarter_turns = ((order % 4) + 4) % 4;
  const auto turn = [quarter_turns](std::complex<double> x) {
    switch (quarter_turns) {
      case 1:
        return std::complex<double>(-x.imag(), x.real());
      case 2:
        return -x;
      case 3:
        return std::complex<double>(x.imag(), -x.real());
      default:
        return x;
    }
  };
  for (Eigen::Index k = 0; k < bins_; ++k) {
    const double f = static_cast<double>(k) * df;
    const double w = spectral_window(f, options, integrating);
    if (w == 0.0) continue;
    // The Nyquist bin of an even-length real signal is real; a derivative of odd order would
    // make it imaginary, which the c2r transform cannot represent: drop it.
    if (k == bins_ - 1 && size_ % 2 == 0 && std::abs(order) % 2 == 1) continue;
    const double omega = 2.0 * std::numbers::pi * f;
    double factor = w * scale;
    for (int i = 0; i < std::abs(order); ++i) factor = order > 0 ? factor * omega : factor / omega;
    spectrum[static_cast<std::size_t>(k)] += turn(factor * spectrum_[static_cast<std::size_t>(k)]);
  }
}

Eigen::VectorXd SpectralRecord::inverse(Spectrum& spectrum) const {
  FftwVector<double>& buffer = scratch_samples();
  buffer.resize(static_cast<std::size_t>(size_));
  transform_->inverse(spectrum.data(), buffer.data());
  return Eigen::Map<const Eigen::VectorXd>(buffer.data(), n_);
}

Eigen::VectorXd spectral_derivative(const Eigen::VectorXd& x, double sample_rate_hz, int order,
                                    const SpectralOptions& options) {
  if (x.size() < 2) return Eigen::VectorXd::Zero(x.size());
  const SpectralRecord record(x, sample_rate_hz);
  SpectralRecord::Spectrum spectrum = record.zero_spectrum();
  record.accumulate(spectrum, 1.0, order, options);
  return record.inverse(spectrum);
}

}  // namespace oscilab::analysis
