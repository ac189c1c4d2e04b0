// The live monitor's spectrum of z (analysis/signal/amplitude_spectrum) against sines of known
// amplitude on whole bins, where the Hann-windowed DFT is exact.
#include "analysis/signal/amplitude_spectrum.h"

#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

namespace oscilab::analysis {
namespace {

TEST(ZSpectrum, ReadsTheHarmonicsAmplitudesAndTheSubharmonic) {
  // 4 s at 512 Hz of z̄ + A1 sin(2π 9 t) + A3 sin(2π 27 t + 0.3): an integer number of periods,
  // so the Hann-windowed DFT at h ν is exact (its leakage vanishes at whole bins).
  const double rate = 512, nu = 9.0, a1 = 2e-3, a3 = 5e-5;
  std::vector<double> z;
  for (int i = 0; i < 2048; ++i) {
    const double t = i / rate;
    z.push_back(0.0028 + a1 * std::sin(2 * std::numbers::pi * nu * t) +
                a3 * std::sin(2 * std::numbers::pi * 3 * nu * t + 0.3));
  }
  z.push_back(std::nan(""));  // the derived tail not computed yet
  const ZSpectrum s = z_spectrum(z, rate, nu, 8);
  EXPECT_DOUBLE_EQ(s.duration_s, 4.0);
  ASSERT_EQ(s.harmonic_amplitude_m.size(), 8u);
  EXPECT_NEAR(s.harmonic_amplitude_m[0], a1, 1e-9 * a1);
  EXPECT_NEAR(s.harmonic_amplitude_m[1], 0.0, 1e-9 * a1);
  EXPECT_NEAR(s.harmonic_amplitude_m[2], a3, 1e-9 * a1);
  EXPECT_EQ(s.harmonic_freq_hz[2], 27.0);
  EXPECT_LT(s.subharmonic_amplitude_m, 1e-3 * a1);  // ν/2 is 18 bins from any component
  // The full spectrum: the bin at 9 Hz (bin 36 of 0.25 Hz) reads A1 (conventions.md scaling).
  EXPECT_DOUBLE_EQ(s.freq_hz[36], 9.0);
  EXPECT_NEAR(s.amplitude_m[36], a1, 1e-9 * a1);

  // A period doubling: a component at ν/2 reads its amplitude.
  for (int i = 0; i < 2048; ++i)
    z[std::size_t(i)] += 1e-4 * std::sin(std::numbers::pi * nu * i / rate);
  EXPECT_NEAR(z_spectrum(z, rate, nu, 8).subharmonic_amplitude_m, 1e-4, 1e-9);
  EXPECT_TRUE(z_spectrum(std::vector<double>(40, 0.0), rate, nu).freq_hz.empty());
}

}  // namespace
}  // namespace oscilab::analysis
