#pragma once

#include <complex>
#include <vector>

#include "analysis/signal/fftw_planner.h"
#include "analysis/signal/real_fft.h"

#include <Eigen/Core>

namespace oscilab::analysis {

/// Zero-phase integration and differentiation in the frequency domain (FFTW), for offline work.
///
/// A record is extended by its mirror image (even extension, length 2N, padded to a fast FFT
/// size) so that the periodic signal the DFT sees has no jump at the ends, transformed,
/// multiplied by (iω)^order and by a real, zero-phase band window, and transformed back
/// (conventions: docs/conventions.md).
///
/// Integration (order < 0) divides by (iω)^|order|, which blows up towards DC: below
/// `highpass_hz` the window is 0 and it rises to 1 by 2·highpass_hz along a raised cosine, so a
/// sensor bias, its slow drift and the integration constants never enter. Differentiation
/// (order > 0) multiplies by (iω)^order, which amplifies noise: above `lowpass_hz` the window
/// falls to 0 by 1.25·lowpass_hz along a raised cosine. The window is real and even, so no phase
/// is added at any frequency: a 9 Hz sine integrates to exactly −1/ω² times itself.
struct SpectralOptions {
  double highpass_hz = 0.0;  // 0: keep all but DC (DC is always dropped when integrating)
  double lowpass_hz = 0.0;   // 0: no low-pass
};

/// The band window of SpectralOptions at frequency f (for documentation plots and tests).
double spectral_window(double f_hz, const SpectralOptions& options, bool integrating);

/// One record's spectrum, transformed once; derivatives and integrals of any order, and sums
/// of them over several records of the same length and rate (z = y − b in one transform), are
/// then a multiplication and one inverse transform each.
class SpectralRecord {
 public:
  using Spectrum = FftwVector<std::complex<double>>;  // aligned for RealFft

  SpectralRecord(const Eigen::VectorXd& x, double sample_rate_hz);  // throws InputError

  /// spectrum += gain · window · (iω)^order · X.
  void accumulate(Spectrum& spectrum, double gain, int order, const SpectralOptions& options) const;
  /// A zero spectrum of this record's size, to accumulate into.
  Spectrum zero_spectrum() const { return Spectrum(static_cast<std::size_t>(bins_), 0.0); }
  /// Sets `spectrum` to zero at this record's size, reusing its memory.
  void clear(Spectrum& spectrum) const { spectrum.assign(static_cast<std::size_t>(bins_), 0.0); }
  /// Back to the time domain: the record's N samples of the inverse transform. The spectrum is
  /// used as scratch and left undefined (FFTW's complex-to-real transform overwrites its input).
  Eigen::VectorXd inverse(Spectrum& spectrum) const;

 private:
  Eigen::Index n_ = 0;     // record length
  Eigen::Index size_ = 0;  // transform length (≥ 2n, fast)
  Eigen::Index bins_ = 0;
  double sample_rate_hz_ = 0.0;
  const RealFft* transform_ = nullptr;  // of length size_
  Spectrum spectrum_;
};

/// Returns d^order x / dt^order (order > 0) or the order-fold integral (order < 0) of a record
/// sampled at `sample_rate_hz`. order == 0 only filters.
Eigen::VectorXd spectral_derivative(const Eigen::VectorXd& x, double sample_rate_hz, int order,
                                    const SpectralOptions& options);

}  // namespace oscilab::analysis
