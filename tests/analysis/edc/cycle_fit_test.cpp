#include "analysis/edc/cycle_analyzer.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace oscilab::analysis {
namespace {

// A synthetic steady response: table b = B sin ωt, relative z = Z0 + Σ_h A_h sin(hωt − φ_h).
struct Synthetic {
  double freq_hz = 9.0, mass_kg = 0.26, b_amp_m = 2e-4, z0_m = 0.0237;
  std::vector<double> amp_m = {5e-3, 0.0, 3e-4, 0.0, 8e-5};
  std::vector<double> lag_rad = {1.1, 0.0, 0.4, 0.0, -0.7};
  double b(double t) const { return b_amp_m * std::sin(2 * std::numbers::pi * freq_hz * t); }
  double b_ddot(double t) const {
    const double w = 2 * std::numbers::pi * freq_hz;
    return -w * w * b(t);
  }
  double z(double t) const {
    double v = z0_m;
    for (std::size_t h = 0; h < amp_m.size(); ++h) {
      v += amp_m[h] * std::sin((h + 1) * 2 * std::numbers::pi * freq_hz * t - lag_rad[h]);
    }
    return v;
  }
  double z_dot(double t) const {
    double v = 0.0;
    for (std::size_t h = 0; h < amp_m.size(); ++h) {
      const double hw = (h + 1) * 2 * std::numbers::pi * freq_hz;
      v += hw * amp_m[h] * std::cos(hw * t - lag_rad[h]);
    }
    return v;
  }
  // ∮ f dz with f = −m b̈ = m ω² B sin ωt: only the first harmonic of z contributes,
  // S = π f0 A₁ sin φ₁ (eq. (13) in our sign, docs/conventions.md).
  double edc() const {
    const double w = 2 * std::numbers::pi * freq_hz;
    return std::numbers::pi * mass_kg * w * w * b_amp_m * amp_m[0] * std::sin(lag_rad[0]);
  }
};

std::vector<CycleFit> analyse(const Synthetic& s, double rate_hz, MotionQuantity mass_quantity,
                              double seconds, int harmonics) {
  CycleAnalyzer::Options options;
  options.fit.freq_hz = s.freq_hz;
  options.fit.mass_kg = s.mass_kg;
  options.fit.harmonics = harmonics;
  options.fit.mass_quantity = mass_quantity;
  options.sample_rate_hz = rate_hz;
  options.t0_s = 0.05;  // cycles need not start at the force's zero phase
  CycleAnalyzer analyzer(options);
  std::vector<CycleFit> cycles;
  const auto n = static_cast<int>(seconds * rate_hz);
  for (int i = 0; i < n; ++i) {
    const double t = i / rate_hz;
    const double base = s.b_ddot(t);
    const double mass = mass_quantity == MotionQuantity::Velocity
                            ? s.z_dot(t) + 2 * std::numbers::pi * s.freq_hz * s.b_amp_m *
                                               std::cos(2 * std::numbers::pi * s.freq_hz * t)
                            : s.z(t) + s.b(t);
    analyzer.push(&t, &base, &mass, 1, cycles);
  }
  return cycles;
}

TEST(CycleFit, RecoversTheExactEnergyOfAMultiHarmonicResponse) {
  const Synthetic s;
  const auto cycles = analyse(s, 512.0, MotionQuantity::Displacement, 3.0, 8);
  ASSERT_GE(cycles.size(), 25u);
  for (const CycleFit& c : cycles) {
    // Noise-free band-limited data: least squares is exact up to rounding (~1e-12 relative).
    EXPECT_NEAR(c.edc_j / s.edc(), 1.0, 1e-9);
    EXPECT_NEAR(c.edc_eq13_j / s.edc(), 1.0, 1e-9);
    EXPECT_NEAR(c.f0_n, s.mass_kg * std::pow(2 * std::numbers::pi * s.freq_hz, 2) * s.b_amp_m,
                1e-12);
    EXPECT_NEAR(c.z_mean_m, s.z0_m, 1e-12);
    EXPECT_NEAR(c.lag_rad, s.lag_rad[0], 1e-9);
    // The trapezoid on 57 samples per cycle is biased by O((ωΔt)²) ≈ 1e-3.
    EXPECT_NEAR(c.edc_trapz_j / s.edc(), 1.0, 3e-3);
  }
}

TEST(CycleFit, VelocityChannelGivesTheSameEnergy) {
  const Synthetic s;
  const auto cycles = analyse(s, 512.0, MotionQuantity::Velocity, 2.0, 8);
  ASSERT_GE(cycles.size(), 15u);
  for (const CycleFit& c : cycles) EXPECT_NEAR(c.edc_j / s.edc(), 1.0, 1e-9);
}

TEST(CycleFit, SevenSamplesPerCycleStillGiveTheFourierEstimate) {
  // 64 Hz at 9 Hz: 7.1 samples per cycle leave room for H = 2 only. With a response of two
  // harmonics the fit is still exact; the trapezoid is not (bias of order (ωΔt)²/12 ≈ 6 %).
  Synthetic s;
  s.amp_m = {5e-3, 4e-4};
  s.lag_rad = {1.1, 0.2};
  const auto cycles = analyse(s, 64.0, MotionQuantity::Displacement, 5.0, 8);
  ASSERT_GE(cycles.size(), 40u);
  for (const CycleFit& c : cycles) {
    EXPECT_EQ(c.z_h.size(), 2u);
    EXPECT_NEAR(c.edc_j / s.edc(), 1.0, 1e-9);
  }
}

TEST(CycleAnalyzer, BlockSizeDoesNotChangeTheCycles) {
  const Synthetic s;
  CycleAnalyzer::Options options;
  options.fit.freq_hz = s.freq_hz;
  options.fit.mass_kg = s.mass_kg;
  options.sample_rate_hz = 512.0;
  const int n = 2000;
  std::vector<double> t(n), base(n), mass(n);
  for (int i = 0; i < n; ++i) {
    t[i] = i / 512.0;
    base[i] = s.b_ddot(t[i]);
    mass[i] = s.z(t[i]) + s.b(t[i]);
  }
  std::vector<CycleFit> whole, pieces;
  CycleAnalyzer(options).push(t.data(), base.data(), mass.data(), n, whole);
  CycleAnalyzer streaming(options);
  for (int i = 0, size = 1; i < n; i += size, size = size % 97 + 13) {
    const int count = std::min(size, n - i);
    streaming.push(t.data() + i, base.data() + i, mass.data() + i, count, pieces);
  }
  ASSERT_EQ(whole.size(), pieces.size());
  for (std::size_t k = 0; k < whole.size(); ++k) EXPECT_EQ(whole[k].edc_j, pieces[k].edc_j);
}

TEST(CycleAnalyzer, SkipsACycleWithAGap) {
  const Synthetic s;
  CycleAnalyzer::Options options;
  options.fit.freq_hz = s.freq_hz;
  options.fit.mass_kg = s.mass_kg;
  options.sample_rate_hz = 512.0;
  CycleAnalyzer analyzer(options);
  std::vector<CycleFit> cycles;
  for (int i = 0; i < 1024; ++i) {
    if (i >= 300 && i < 330) continue;  // 30 samples lost inside the sixth cycle
    const double t = i / 512.0, base = s.b_ddot(t), mass = s.z(t) + s.b(t);
    analyzer.push(&t, &base, &mass, 1, cycles);
  }
  // 2 s hold 17 whole cycles; the one with the gap is not fitted.
  EXPECT_EQ(cycles.size(), 16u);
  for (const CycleFit& c : cycles) EXPECT_NEAR(c.edc_j / s.edc(), 1.0, 1e-9);
}

}  // namespace
}  // namespace oscilab::analysis
