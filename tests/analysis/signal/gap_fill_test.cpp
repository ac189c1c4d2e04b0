#include "analysis/signal/gap_fill.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>

namespace oscilab::analysis {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

bool same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

TEST(GapFill, SignalWithoutGapIsUnchangedBitForBit) {
  Eigen::VectorXd x(1000);
  for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = std::sin(0.37 * i) * 1e-3 + 1e-300 * i;
  x[17] = -0.0;  // a negative zero stays a negative zero
  x[18] = std::numeric_limits<double>::denorm_min();
  const Eigen::VectorXd before = x;
  EXPECT_EQ(fill_non_finite(x), 0);
  EXPECT_TRUE(same_bits(x, before));
  EXPECT_TRUE(std::signbit(x[17]));
}

TEST(GapFill, EmptySignalIsLeftAlone) {
  Eigen::VectorXd x(0);
  EXPECT_EQ(fill_non_finite(x), 0);
  EXPECT_EQ(x.size(), 0);
}

// The fill is the chord between the finite samples on either side, so a straight line across a
// gap comes back as itself. Both ends are exact samples of the line and the chord is evaluated
// as left + s·(right − left), so the error is a few ulps of the values (≤ 1e-15 relative here).
TEST(GapFill, StraightLineAcrossGapsIsReproduced) {
  const double offset = 0.25, slope = 3e-3;  // any units per sample
  Eigen::VectorXd truth(200), x(200);
  for (Eigen::Index i = 0; i < truth.size(); ++i)
    truth[i] = offset + slope * static_cast<double>(i);
  x = truth;
  for (Eigen::Index i = 20; i < 57; ++i) x[i] = kNaN;  // 37 samples
  x[100] = kInf;                                       // one sample, +∞
  for (Eigen::Index i = 150; i < 153; ++i) x[i] = -kInf;
  const Eigen::VectorXd before = x;
  EXPECT_EQ(fill_non_finite(x), 37 + 1 + 3);
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    ASSERT_TRUE(std::isfinite(x[i])) << "sample " << i;
    EXPECT_NEAR(x[i], truth[i], 1e-15 * std::abs(truth[i])) << "sample " << i;
    // Finite samples are never touched.
    if (std::isfinite(before[i])) {
      EXPECT_EQ(std::memcmp(&x[i], &before[i], sizeof(double)), 0) << i;
    }
  }
  // A one-sample gap is the mean of its neighbours: left + ½(right − left).
  EXPECT_DOUBLE_EQ(x[100], before[99] + 0.5 * (before[101] - before[99]));
}

// A pure sine across a gap: the chord's error is known in closed form. For a gap centred on a
// crest with g (odd) missing samples, the chord joins two samples at ±h/2 around the crest,
// h = (g + 1)·dt, both at A cos(ωh/2): the middle sample becomes exactly that, an error of
// A(1 − cos(ωh/2)) ≤ A ω² h²/8, the bound of linear interpolation, (h²/8)·max|f''|, which every
// other filled sample obeys too.
TEST(GapFill, SineAcrossAGapFollowsTheChordWithinTheInterpolationBound) {
  const double rate_hz = 512.0, freq_hz = 9.0, amplitude = 2e-3;
  const double w = 2 * std::numbers::pi * freq_hz;
  const Eigen::Index n = 2048, g = 11;
  // Crest at t_c = 1/(4f) + k/f; place it on a sample: choose t_c = 100 dt exactly by phase.
  const Eigen::Index crest = 100;
  const double phase = std::numbers::pi / 2 - w * static_cast<double>(crest) / rate_hz;
  Eigen::VectorXd truth(n), x(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    truth[i] = amplitude * std::sin(w * static_cast<double>(i) / rate_hz + phase);
  }
  x = truth;
  for (Eigen::Index i = crest - g / 2; i <= crest + g / 2; ++i) x[i] = kNaN;
  EXPECT_EQ(fill_non_finite(x), g);

  const double h_s = static_cast<double>(g + 1) / rate_hz;
  // The two ends are sampled sines; cos evaluated in the test differs from them by rounding.
  EXPECT_NEAR(x[crest], amplitude * std::cos(w * h_s / 2), 1e-15);
  const double bound = amplitude * w * w * h_s * h_s / 8;
  EXPECT_NEAR(truth[crest] - x[crest], amplitude * (1 - std::cos(w * h_s / 2)), 1e-15);
  for (Eigen::Index i = crest - g / 2; i <= crest + g / 2; ++i) {
    EXPECT_LE(std::abs(x[i] - truth[i]), bound) << "sample " << i;
    // The chord lies under a crest (f'' < 0 there): never above the truth.
    EXPECT_LE(x[i], truth[i]) << "sample " << i;
  }
}

// At an end there is one neighbour only: the fill holds the nearest finite sample.
TEST(GapFill, EdgeGapsHoldTheNearestFiniteSample) {
  Eigen::VectorXd x(10);
  x << kNaN, kNaN, kInf, 1.5, 2.5, 3.5, 4.5, kNaN, -kInf, kNaN;
  EXPECT_EQ(fill_non_finite(x), 6);
  Eigen::VectorXd expected(10);
  expected << 1.5, 1.5, 1.5, 1.5, 2.5, 3.5, 4.5, 4.5, 4.5, 4.5;
  EXPECT_TRUE(same_bits(x, expected)) << x.transpose();
}

TEST(GapFill, SingleFiniteSampleFillsEverything) {
  Eigen::VectorXd x(5);
  x << kNaN, kNaN, -7.25, kNaN, kNaN;
  EXPECT_EQ(fill_non_finite(x), 4);
  EXPECT_TRUE(same_bits(x, Eigen::VectorXd::Constant(5, -7.25))) << x.transpose();
}

TEST(GapFill, AllNonFiniteSignalBecomesZeros) {
  Eigen::VectorXd x(7);
  x << kNaN, kInf, -kInf, kNaN, kNaN, kInf, kNaN;
  EXPECT_EQ(fill_non_finite(x), 7);
  // Plain +0.0, not −0.0: the fill is 0 + s·(0 − 0).
  EXPECT_TRUE(same_bits(x, Eigen::VectorXd::Zero(7))) << x.transpose();
}

}  // namespace
}  // namespace oscilab::analysis
