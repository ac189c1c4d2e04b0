#include "analysis/signal/ac_coupling.h"

#include <cmath>
#include <numbers>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {

std::complex<double> first_order_highpass(double freq_hz, double corner_hz) {
  const std::complex<double> jw(0.0, 2.0 * std::numbers::pi * freq_hz);
  return jw / (jw + 2.0 * std::numbers::pi * corner_hz);
}

AcCouplingInverse::AcCouplingInverse(double corner_hz, double sample_rate_hz,
                                     const std::string& where, double leak_ratio)
    : sample_rate_hz_(sample_rate_hz) {
  if (!(sample_rate_hz > 0) || !std::isfinite(sample_rate_hz) || !(corner_hz > 0) ||
      !(corner_hz < 0.5 * sample_rate_hz)) {
    throw InputError(where + ": AC-coupling corner " + std::to_string(corner_hz) +
                     " Hz must be positive and below the Nyquist frequency " +
                     std::to_string(0.5 * sample_rate_hz) + " Hz");
  }
  if (!(leak_ratio > 1) || !std::isfinite(leak_ratio)) {
    throw InputError(where + ": AC-coupling leak ratio " + std::to_string(leak_ratio) +
                     " must be above 1");
  }
  const double k = 2.0 * sample_rate_hz;
  const double wc = 2.0 * std::numbers::pi * corner_hz;
  const double wl = wc / leak_ratio;
  b0_ = (k + wc) / (k + wl);
  b1_ = (wc - k) / (k + wl);
  a1_ = (wl - k) / (k + wl);
}

double AcCouplingInverse::push(double y) {
  if (!std::isfinite(y)) return std::nan("");
  const double x = b0_ * y + b1_ * y_prev_ - a1_ * x_prev_;
  y_prev_ = y;
  x_prev_ = x;
  return x;
}

std::complex<double> AcCouplingInverse::response(double freq_hz) const {
  const std::complex<double> z_inv =
      std::polar(1.0, -2.0 * std::numbers::pi * freq_hz / sample_rate_hz_);
  return (b0_ + b1_ * z_inv) / (1.0 + a1_ * z_inv);
}

}  // namespace oscilab::analysis
