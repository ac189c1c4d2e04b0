#pragma once

#include <complex>
#include <string>

namespace oscilab::analysis {

/// The frequency response of a first-order high-pass of corner fc, as the input capacitor of an
/// AC-coupled sound-card input puts in front of the samples:
///
///   H(jω) = jω / (jω + ωc),  ωc = 2π fc,   |H| = ω / √(ω² + ωc²),  arg H = atan(ωc / ω) (a lead).
///
/// At ω = 10 ωc the lead is 0.0997 rad and the gain −0.5 %; at ω = ωc, π/4 and −3 dB.
std::complex<double> first_order_highpass(double freq_hz, double corner_hz);

/// Undoes a first-order high-pass, sample by sample: the inverse G(s) = (s + ωc) / s, made
/// usable by moving its integrating pole to a small leak ωl = ωc / leak_ratio,
///
///   G(s) = (s + ωc) / (s + ωl),   so that G·H = s / (s + ωl):
///
/// what is left is a high-pass at fc / leak_ratio. With the default ratio 100 the residual phase
/// lead at f is atan(fc / (100 f)): 1 mrad at f = 10 fc (where Acquisition warns), 2.2 mrad for a
/// 2 Hz corner at 9 Hz, against 0.219 rad uncorrected. A constant offset at the input comes out
/// × leak_ratio (the loop area, ∮ f dz, does not depend on a constant offset of f or z); a start
/// or a gap settles with the time constant leak_ratio / ωc (8 s for fc = 2 Hz).
///
/// Discretised by the bilinear transform s = 2 fs (1 − z⁻¹) / (1 + z⁻¹) (Oppenheim & Schafer,
/// "Discrete-Time Signal Processing", §7.2): frequencies warp by (fs/π) tan(π f / fs), 0.1 % at
/// 9 Hz and 512 Hz, which changes the corrected phase by about 0.1 % of atan(fc / f).
///
///   x[n] = ((2fs + ωc) y[n] + (ωc − 2fs) y[n−1] − (ωl − 2fs) x[n−1]) / (2fs + ωl)
///
/// A non-finite input gives a NaN output and leaves the state as it was (a gap: the missing
/// stretch of a zero-mean signal's integral shows as a slowly decaying offset, see above).
/// Not thread-safe: one producer.
class AcCouplingInverse {
 public:
  /// Throws InputError naming `where` unless 0 < corner_hz < sample_rate_hz / 2 and
  /// leak_ratio > 1.
  AcCouplingInverse(double corner_hz, double sample_rate_hz, const std::string& where,
                    double leak_ratio = 100.0);

  double push(double y);
  /// The discrete filter's own response at freq_hz (for tests and documentation).
  std::complex<double> response(double freq_hz) const;

 private:
  double b0_, b1_, a1_;  // x[n] = b0 y[n] + b1 y[n−1] − a1 x[n−1]
  double sample_rate_hz_;
  double y_prev_ = 0.0, x_prev_ = 0.0;
};

}  // namespace oscilab::analysis
