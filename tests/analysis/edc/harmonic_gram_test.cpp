// The closed-form Gram matrix of the cycle fit's basis against the sum of its rows' products
// (a second method), and its refusal where the closed form divides by almost zero.
#include "analysis/edc/harmonic_gram.h"

#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

namespace oscilab::analysis {
namespace {

// AᵀA by definition, with the basis of cycle_fit.h: 1, τ, cos hθ, −sin hθ.
Eigen::MatrixXd summed_gram(int n, double theta0, double dtheta, double tau0, double dt,
                            int h_max) {
  const int columns = 2 + 2 * h_max;
  Eigen::MatrixXd basis(n, columns);
  for (int j = 0; j < n; ++j) {
    const double theta = theta0 + j * dtheta;
    basis(j, 0) = 1.0;
    basis(j, 1) = tau0 + j * dt;
    for (int h = 1; h <= h_max; ++h) {
      basis(j, 2 * h) = std::cos(h * theta);
      basis(j, 2 * h + 1) = -std::sin(h * theta);
    }
  }
  return basis.transpose() * basis;
}

// Cycles as the EDC path meets them: 9 Hz at 512 Hz (57 samples), 2 Hz at 512 Hz, 40 Hz at
// 2 kHz, 1 Hz at 100 Hz, with H from 1 to 8, random phase and window offsets. The tolerance is
// 1e-12 of the largest entry (n): the closed form's rounding is below n ε / 0.03 ≈ 7e-15 n
// (harmonic_gram.h) and the summed products' below n ε; a wrong identity or sign is off by
// O(1) of an entry.
TEST(HarmonicGram, EqualsTheSumOfTheRowsProducts) {
  std::mt19937 generator(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  struct Case {
    double freq_hz, rate_hz;
    int harmonics;
  };
  int compared = 0;
  for (const Case c : {Case{9, 512, 8}, Case{9, 512, 1}, Case{2, 512, 8}, Case{40, 2048, 5},
                       Case{1, 100, 3}, Case{9.3, 512, 8}}) {
    for (int trial = 0; trial < 5; ++trial) {
      const double dt = 1.0 / c.rate_hz;
      const double omega = 2.0 * std::numbers::pi * c.freq_hz;
      const int n = static_cast<int>(std::floor(c.rate_hz / c.freq_hz)) - (trial % 2);
      const double offset = unit(generator) * dt;  // first sample after the window's start
      // A phase within the first turn: at a phase of θ rad both methods round the angle to
      // about ε θ, which alone would part them by n 2H ε θ.
      const double theta0 = 2.0 * std::numbers::pi * unit(generator) + omega * offset;
      const double tau0 = offset - 0.5 / c.freq_hz;  // τ = t − t_mid
      Eigen::MatrixXd closed;
      ASSERT_TRUE(harmonic_gram_evenly_spaced(n, theta0, omega * dt, tau0, dt, c.harmonics, closed))
          << c.freq_hz << " Hz at " << c.rate_hz << " Hz";
      const Eigen::MatrixXd summed = summed_gram(n, theta0, omega * dt, tau0, dt, c.harmonics);
      ASSERT_EQ(closed.rows(), summed.rows());
      EXPECT_LT((closed - summed).cwiseAbs().maxCoeff(), 1e-12 * n)
          << c.freq_hz << " Hz at " << c.rate_hz << " Hz, H = " << c.harmonics << ", n = " << n;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 30);
}

// Where a harmonic order up to 2H sits at a whole number of turns per sample (here order 16 of
// 32 Hz at 512 Hz: kΔθ = 2π), the closed form's denominators vanish: it declines, and the
// cycle fit sums the products instead.
TEST(HarmonicGram, DeclinesWhereAnOrderIsAWholeTurnPerSample) {
  const double dt = 1.0 / 512.0;
  const double dtheta = 2.0 * std::numbers::pi * 32.0 * dt;
  Eigen::MatrixXd gram;
  EXPECT_FALSE(harmonic_gram_evenly_spaced(16, 0.3, dtheta, -0.01, dt, 8, gram));
  // With H = 7 the highest order is 14: accepted, and right.
  ASSERT_TRUE(harmonic_gram_evenly_spaced(16, 0.3, dtheta, -0.01, dt, 7, gram));
  EXPECT_LT((gram - summed_gram(16, 0.3, dtheta, -0.01, dt, 7)).cwiseAbs().maxCoeff(), 1e-12 * 16);
}

}  // namespace
}  // namespace oscilab::analysis
