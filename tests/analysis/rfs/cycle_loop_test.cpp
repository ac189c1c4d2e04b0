// The force–displacement loop of the newest cycle against the closed-form loop area of Eq. (13).
#include "analysis/rfs/cycle_loop.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <numbers>

namespace oscilab::analysis {
namespace {

TEST(NewestCycleLoop, EnclosesTheEnergyOfEq13) {
  // f = f0 sin ωt, z = z̄ + Z sin(ωt − θ): ∮ f dz = π f0 Z sin θ (docs/conventions.md, eq. (13)).
  const double rate = 512, nu = 8.0, f0 = 1.3, zz = 0.002, theta = 0.4,
               w = 2 * std::numbers::pi * nu;
  std::vector<double> t_s, z_m, f_n;
  for (int i = 0; i < 512; ++i) {
    const double t = i / rate;
    t_s.push_back(t);
    f_n.push_back(f0 * std::sin(w * t));
    z_m.push_back(i < 500 ? -0.0028 + zz * std::sin(w * t - theta) : std::nan(""));
  }
  const CycleLoop loop = newest_cycle_loop(t_s, z_m, f_n, nu);
  ASSERT_EQ(loop.z_m.size(), 65u);  // one period of 64 samples, closed
  EXPECT_NEAR(loop.end_s, 499.0 / rate, 1e-12);
  EXPECT_FALSE(loop.positive);
  double area = 0;
  for (std::size_t i = 0; i + 1 < loop.z_m.size(); ++i) {
    area += 0.5 * (loop.f_n[i] + loop.f_n[i + 1]) * (loop.z_m[i + 1] - loop.z_m[i]);
  }
  // The trapezoid on 64 samples per period: relative error (ωΔt)²/12 ≈ 8e-4.
  EXPECT_NEAR(area / (std::numbers::pi * f0 * zz * std::sin(theta)), 1.0, 2e-3);
  // A 10 s cycle: not in 1 s of samples.
  EXPECT_TRUE(newest_cycle_loop(t_s, z_m, f_n, 0.1).z_m.empty());
}

}  // namespace
}  // namespace oscilab::analysis
