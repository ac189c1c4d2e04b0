#include "analysis/pipeline/derived_signals.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <numbers>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {
namespace {

constexpr double kRateHz = 512.0;

// A table moving as b = A sin ωt and a mass whose relative motion is z = Z sin(ωt + φ): the
// channels an accelerometer (b̈) and a vibrometer (y = b + z) give, in closed form.
struct Motion {
  double a_m = 2e-3, z_m = 5e-3, phase = 0.7, freq_hz = 9.0, mass_kg = 0.3;
  double w() const { return 2 * std::numbers::pi * freq_hz; }
  double b(double t) const { return a_m * std::sin(w() * t); }
  double b_ddot(double t) const { return -w() * w() * b(t); }
  double z(double t) const { return z_m * std::sin(w() * t + phase); }
  double z_dot(double t) const { return z_m * w() * std::cos(w() * t + phase); }
  double z_ddot(double t) const { return -w() * w() * z(t); }
  double y(double t) const { return b(t) + z(t); }
};

DerivedSignals::Options options(double latency_s, int max_rows) {
  DerivedSignals::Options o;
  o.sample_rate_hz = kRateHz;
  o.mass_kg = Motion().mass_kg;
  o.latency_s = latency_s;
  o.max_rows = max_rows;
  o.derivative_lowpass_hz = 60.0;
  return o;
}

// Feeds `seconds` of the motion in blocks of 16 and collects every derived value by sample.
struct Collected {
  std::vector<double> b, z, z_dot, r;
};
Collected run(DerivedSignals& derived, const Motion& m, double seconds, bool relative,
              std::uint64_t fault = ~0ULL) {
  const int rows = 16;
  const auto n = static_cast<std::uint64_t>(seconds * kRateHz);
  Collected out;
  for (auto* v : {&out.b, &out.z, &out.z_dot, &out.r}) v->assign(n, std::nan(""));
  DerivedSignals::Block block = derived.make_block();
  std::vector<double> base(rows), mass(rows);
  for (std::uint64_t first = 0; first + rows <= n; first += rows) {
    for (int r = 0; r < rows; ++r) {
      const double t = static_cast<double>(first + static_cast<std::uint64_t>(r)) / kRateHz;
      base[static_cast<std::size_t>(r)] = m.b_ddot(t);
      mass[static_cast<std::size_t>(r)] = relative ? m.z(t) : m.y(t);
      if (first + static_cast<std::uint64_t>(r) == fault) {
        base[static_cast<std::size_t>(r)] = mass[static_cast<std::size_t>(r)] = 0.0;
        derived.exclude(fault, fault);
      }
    }
    derived.push(first, base.data(), mass.data(), rows, block);
    for (int k = 0; k < block.count; ++k) {
      const auto at = static_cast<std::size_t>(block.first_sample) + static_cast<std::size_t>(k);
      out.b[at] = block.b_m[static_cast<std::size_t>(k)];
      out.z[at] = block.z_m[static_cast<std::size_t>(k)];
      out.z_dot[at] = block.z_dot_m_s[static_cast<std::size_t>(k)];
      out.r[at] = block.restoring_force_n[static_cast<std::size_t>(k)];
    }
  }
  return out;
}

// With a 4 s latency the streaming integrator reproduces a 9 Hz sine's double integral to 1e-4 of
// its amplitude (its own test); the differences and derivatives here add a few times that, so
// 1e-3 of each signal's amplitude bounds the truncation of the filters, not luck.
TEST(DerivedSignals, GivesEq1sSignalsOfAClosedFormMotionWithItsLatency) {
  const Motion m;
  DerivedSignals derived(options(4.0, 16));
  const int latency = derived.latency_samples();
  EXPECT_EQ(latency, static_cast<int>(4.0 * kRateHz));
  const Collected c = run(derived, m, 20.0, false);
  int checked = 0;
  for (std::size_t i = 0; i < c.b.size(); ++i) {
    if (!std::isfinite(c.z[i])) continue;
    const double t = static_cast<double>(i) / kRateHz;
    EXPECT_NEAR(c.b[i], m.b(t), 1e-3 * m.a_m) << t;
    EXPECT_NEAR(c.z[i], m.z(t), 1e-3 * m.z_m) << t;
    EXPECT_NEAR(c.z_dot[i], m.z_dot(t), 1e-3 * m.z_m * m.w()) << t;
    // R = f − m z̈ = −m (b̈ + z̈) = −m ÿ (eq. (1))
    const double r = -m.mass_kg * (m.b_ddot(t) + m.z_ddot(t));
    EXPECT_NEAR(c.r[i], r, 1e-3 * m.mass_kg * m.w() * m.w() * (m.a_m + m.z_m)) << t;
    ++checked;
  }
  // Every sample from the first full filter on (the first 2 × latency inputs fill it) up to the
  // newest minus the latency, less the last block's partial rows.
  EXPECT_GE(checked, static_cast<int>(20.0 * kRateHz) - 3 * latency - 16);
  EXPECT_GT(checked, 0);
}

TEST(DerivedSignals, ARelativeMassChannelGivesZItselfAndRFromTheForce) {
  const Motion m;
  DerivedSignals::Options o = options(4.0, 16);
  o.mass_is_relative = true;
  DerivedSignals derived(o);
  const Collected c = run(derived, m, 20.0, true);
  int checked = 0;
  for (std::size_t i = 0; i < c.z.size(); ++i) {
    if (!std::isfinite(c.r[i])) continue;
    const double t = static_cast<double>(i) / kRateHz;
    EXPECT_NEAR(c.z[i], m.z(t), 1e-12);  // the delayed sample itself
    const double r = -m.mass_kg * m.b_ddot(t) - m.mass_kg * m.z_ddot(t);  // f − m z̈
    EXPECT_NEAR(c.r[i], r, 1e-3 * m.mass_kg * m.w() * m.w() * m.z_m) << t;
    ++checked;
  }
  EXPECT_GT(checked, 1000);
}

// A fault at sample s reaches every output whose filter span (±latency) touches it: derived
// samples s − L … s + L are left out, s + L + 1 is trusted again.
TEST(DerivedSignals, LeavesOutExactlyTheValuesWhoseFiltersSawAFault) {
  const Motion m;
  DerivedSignals derived(options(1.0, 16));
  const auto latency = static_cast<std::size_t>(derived.latency_samples());
  const std::size_t fault = 6000;
  const Collected c = run(derived, m, 20.0, false, fault);
  EXPECT_TRUE(std::isfinite(c.z[fault - latency - 1]));
  for (std::size_t at = fault - latency; at <= fault + latency; ++at) {
    ASSERT_TRUE(std::isnan(c.z[at])) << at;
    ASSERT_TRUE(std::isnan(c.r[at])) << at;
  }
  EXPECT_TRUE(std::isfinite(c.z[fault + latency + 1]));
  EXPECT_NEAR(c.z[fault + latency + 1], m.z(static_cast<double>(fault + latency + 1) / kRateHz),
              1e-2 * m.z_m);
}

TEST(DerivedSignals, RefusesBadOptionsAndTooLargeABlock) {
  DerivedSignals::Options o = options(1.0, 16);
  o.mass_kg = 0.0;
  EXPECT_THROW(DerivedSignals{o}, InputError);
  DerivedSignals derived(options(1.0, 16));
  DerivedSignals::Block block = derived.make_block();
  std::vector<double> x(32, 0.0);
  try {
    derived.push(0, x.data(), x.data(), 32, block);
    FAIL() << "a block of 32 rows was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("32 rows"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace oscilab::analysis
