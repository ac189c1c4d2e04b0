#include "analysis/signal/ac_coupling.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"
#include "tests/input_error_of.h"

namespace oscilab::analysis {
namespace {

using oscilab::testing::input_error_of;

TEST(FirstOrderHighpass, IsTheClosedForm) {
  // H(jω) = jω / (jω + ωc): −3 dB and π/4 at the corner, a lead of atan(fc / f) elsewhere.
  const std::complex<double> at_corner = first_order_highpass(2.0, 2.0);
  EXPECT_NEAR(std::abs(at_corner), 1.0 / std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(std::arg(at_corner), std::numbers::pi / 4, 1e-15);
  const std::complex<double> at_9 = first_order_highpass(9.0, 2.0);
  EXPECT_NEAR(std::arg(at_9), std::atan(2.0 / 9.0), 1e-15);
  EXPECT_NEAR(std::abs(at_9), 9.0 / std::sqrt(81.0 + 4.0), 1e-15);
}

// Amplitude and phase of x at f over whole periods (a one-bin DFT), complex: A e^{jφ} for
// A cos(ωt + φ).
std::complex<double> tone(const std::vector<double>& x, std::size_t from, double f_hz,
                          double fs_hz) {
  const auto period = static_cast<std::size_t>(std::llround(fs_hz / f_hz));
  const std::size_t n = (x.size() - from) / period * period;
  std::complex<double> sum = 0.0;
  for (std::size_t i = from; i < from + n; ++i) {
    sum += x[i] * std::polar(1.0, -2 * std::numbers::pi * f_hz * static_cast<double>(i) / fs_hz);
  }
  return 2.0 * sum / static_cast<double>(n);
}

TEST(AcCouplingInverse, UndoesTheHighpassToTheLeakLeftOnPurpose) {
  // y = Re{H(jω) e^{jωt}}, a unit cosine through the closed-form high-pass (fc = 2 Hz) in steady
  // state. The inverse's output is Re{G H e^{jωt}} with G·H = jω/(jω + ωc/100), the stated
  // residual: its phase within 1e-4 rad of atan(fc / 100 f) (the bilinear transform's warping
  // at 8 Hz and 512 Hz changes the correction by ~0.1 % of atan(fc/f) = 2.4e-4 rad,
  // prewarping aside), where the uncorrected lead is atan(fc/f) = 0.245 rad.
  const double fs = 512.0, fc = 2.0, f = 8.0;
  const std::complex<double> h = first_order_highpass(f, fc);
  AcCouplingInverse inverse(fc, fs, "test");
  std::vector<double> out;
  const std::size_t n = 80 * 512;  // 80 s: the leak's 8 s time constant settles 10 times
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / fs;
    out.push_back(inverse.push(std::real(h * std::polar(1.0, 2 * std::numbers::pi * f * t))));
  }
  const std::complex<double> got = tone(out, n / 2, f, fs);
  const double residual_lead = std::atan(fc / 100.0 / f);
  EXPECT_NEAR(std::arg(got), residual_lead, 3e-4);
  EXPECT_NEAR(std::abs(got), 1.0, 1e-3);  // |G H| = 1 − 3e-6: the leak costs no gain
  EXPECT_NEAR(std::arg(h), 0.245, 1e-3);  // what the correction removed
  // The filter's own response is G(jω) = (jω + ωc)/(jω + ωl) up to the warping.
  const std::complex<double> jw(0.0, 2 * std::numbers::pi * f);
  const std::complex<double> g =
      (jw + 2 * std::numbers::pi * fc) / (jw + 2 * std::numbers::pi * fc / 100.0);
  EXPECT_NEAR(std::abs(inverse.response(f) / g - 1.0), 0.0, 5e-4);
}

TEST(AcCouplingInverse, HoldsItsStateOverNonFiniteInput) {
  AcCouplingInverse inverse(1.0, 512.0, "test");
  inverse.push(1.0);
  EXPECT_TRUE(std::isnan(inverse.push(std::nan(""))));
  EXPECT_TRUE(std::isfinite(inverse.push(1.0)));
}

TEST(AcCouplingInverse, RefusesACornerAtOrAboveNyquist) {
  EXPECT_EQ(input_error_of([] { AcCouplingInverse(256.0, 512.0, "run.json: channels[1]"); }),
            "run.json: channels[1]: AC-coupling corner 256.000000 Hz must be positive and below "
            "the Nyquist frequency 256.000000 Hz");
  EXPECT_EQ(input_error_of([] { AcCouplingInverse(1.0, 512.0, "x", 0.5); }),
            "x: AC-coupling leak ratio 0.500000 must be above 1");
}

}  // namespace
}  // namespace oscilab::analysis
