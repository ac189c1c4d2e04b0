// RealFft against the DFT's definition (a direct O(n²) sum in long double) and against FFTW's
// own real transforms (a second method) at a record's length.
#include "analysis/signal/real_fft.h"

#include <cmath>
#include <complex>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"
#include "analysis/signal/fftw_planner.h"

namespace oscilab::analysis {
namespace {

FftwVector<double> random_record(int n, unsigned seed) {
  std::mt19937 generator(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  FftwVector<double> x(static_cast<std::size_t>(n));
  for (double& v : x) v = normal(generator);
  return x;
}

// X_k = Σ_j x_j e^{−2πijk/n}, summed in long double.
std::complex<long double> direct_bin(const FftwVector<double>& x, int k) {
  const auto n = static_cast<long double>(x.size());
  std::complex<long double> sum = 0.0L;
  for (std::size_t j = 0; j < x.size(); ++j) {
    const long double angle = -2.0L * std::numbers::pi_v<long double> *
                              static_cast<long double>(j) * static_cast<long double>(k) / n;
    sum += static_cast<long double>(x[j]) * std::polar(1.0L, angle);
  }
  return sum;
}

class RealFftSizes : public ::testing::TestWithParam<int> {};

// Every bin of the forward transform equals the definition. The tolerance: a DFT by FFT has a
// relative rms error of O(ε log n) against the norm of the record (Higham, "Accuracy and
// Stability of Numerical Algorithms", §24.1), so 1e-13 × ‖x‖ with ‖x‖ ≈ √n covers n ≤ 1000
// with a margin of 100 over ε log₂ n ≈ 2e-15, while any wrong twiddle, sign or pairing gives
// errors of order ‖x‖.
TEST_P(RealFftSizes, ForwardEqualsTheDefinition) {
  const int n = GetParam();
  const FftwVector<double> x = random_record(n, 7u + static_cast<unsigned>(n));
  const RealFft& fft = RealFft::of_size(n);
  ASSERT_EQ(fft.bins(), n / 2 + 1);
  FftwVector<std::complex<double>> spectrum(static_cast<std::size_t>(fft.bins()));
  fft.forward(x.data(), spectrum.data());
  const double tolerance = 1e-13 * std::sqrt(static_cast<double>(n));
  for (int k = 0; k < fft.bins(); ++k) {
    const std::complex<long double> expected = direct_bin(x, k);
    EXPECT_NEAR(spectrum[static_cast<std::size_t>(k)].real(), static_cast<double>(expected.real()),
                tolerance)
        << "n " << n << ", bin " << k;
    EXPECT_NEAR(spectrum[static_cast<std::size_t>(k)].imag(), static_cast<double>(expected.imag()),
                tolerance)
        << "n " << n << ", bin " << k;
  }
}

// inverse(forward(x)) = n x, as FFTW's c2r after its r2c.
TEST_P(RealFftSizes, InverseUndoesForwardTimesN) {
  const int n = GetParam();
  const FftwVector<double> x = random_record(n, 11u + static_cast<unsigned>(n));
  const RealFft& fft = RealFft::of_size(n);
  FftwVector<std::complex<double>> spectrum(static_cast<std::size_t>(fft.bins()));
  fft.forward(x.data(), spectrum.data());
  FftwVector<double> back(static_cast<std::size_t>(n));
  fft.inverse(spectrum.data(), back.data());
  for (int j = 0; j < n; ++j) {
    EXPECT_NEAR(back[static_cast<std::size_t>(j)] / n, x[static_cast<std::size_t>(j)], 1e-13)
        << "n " << n << ", sample " << j;
  }
}

// Even lengths with n/4 whole (reflected twiddles) and not, odd lengths (FFTW's r2c and c2r),
// the smallest ones.
INSTANTIATE_TEST_SUITE_P(Lengths, RealFftSizes,
                         ::testing::Values(2, 3, 4, 6, 8, 10, 12, 15, 30, 64, 90, 125, 250, 1000));

// The inverse reads only the real parts of X_0 and X_{n/2}, as c2r does: a spectrum whose
// ends carry imaginary parts inverts like the same spectrum without them.
TEST(RealFft, InverseIgnoresTheImaginaryPartsOfDcAndNyquist) {
  const int n = 16;
  const RealFft& fft = RealFft::of_size(n);
  FftwVector<std::complex<double>> clean(static_cast<std::size_t>(fft.bins()));
  for (int k = 0; k < fft.bins(); ++k) clean[static_cast<std::size_t>(k)] = {1.0 + k, 0.5 * k};
  clean.front().imag(0.0);
  clean.back().imag(0.0);
  FftwVector<std::complex<double>> dirty = clean;
  dirty.front().imag(3.0);
  dirty.back().imag(-2.0);
  FftwVector<double> a(n), b(n);
  fft.inverse(clean.data(), a.data());
  fft.inverse(dirty.data(), b.data());
  for (int j = 0; j < n; ++j)
    EXPECT_DOUBLE_EQ(a[static_cast<std::size_t>(j)], b[static_cast<std::size_t>(j)]);
}

// At the length the offline analysis meets (the even extension of a 262.5 s record at 512 Hz):
// the same bins and the same inverse as FFTW's r2c and c2r plans, to rounding (1e-12 × ‖x‖
// against an rms error of O(ε log n) ≈ 4e-15 × ‖x‖).
TEST(RealFft, MatchesFftwsRealTransformsAtARecordsLength) {
  const int n = 268800;
  const FftwVector<double> x = random_record(n, 3u);
  const RealFft& fft = RealFft::of_size(n);
  FftwVector<std::complex<double>> ours(static_cast<std::size_t>(fft.bins())), theirs = ours;
  fft.forward(x.data(), ours.data());
  FftwVector<double> scratch = x;
  fftw_plan r2c = nullptr, c2r = nullptr;
  {
    const std::lock_guard lock(fftw_planner_mutex());
    r2c = fftw_plan_dft_r2c_1d(n, scratch.data(), reinterpret_cast<fftw_complex*>(theirs.data()),
                               FFTW_ESTIMATE);
  }
  fftw_execute(r2c);
  const double norm = std::sqrt(static_cast<double>(n));
  double worst = 0.0;
  for (std::size_t k = 0; k < ours.size(); ++k)
    worst = std::max(worst, std::abs(ours[k] - theirs[k]));
  EXPECT_LT(worst, 1e-12 * norm);

  FftwVector<double> ours_back(static_cast<std::size_t>(n)), theirs_back = ours_back;
  fft.inverse(ours.data(), ours_back.data());
  {
    const std::lock_guard lock(fftw_planner_mutex());
    c2r = fftw_plan_dft_c2r_1d(n, reinterpret_cast<fftw_complex*>(theirs.data()),
                               theirs_back.data(), FFTW_ESTIMATE);
  }
  fftw_execute(c2r);
  double worst_back = 0.0;
  for (int j = 0; j < n; ++j) {
    worst_back = std::max(worst_back, std::abs(ours_back[static_cast<std::size_t>(j)] -
                                               theirs_back[static_cast<std::size_t>(j)]));
  }
  EXPECT_LT(worst_back / n, 1e-12);
  {
    const std::lock_guard lock(fftw_planner_mutex());
    fftw_destroy_plan(r2c);
    fftw_destroy_plan(c2r);
  }
}

TEST(RealFft, RefusesLengthsBelowTwo) {
  EXPECT_THROW(RealFft(1), InputError);
  EXPECT_THROW(RealFft(0), InputError);
}

}  // namespace
}  // namespace oscilab::analysis
