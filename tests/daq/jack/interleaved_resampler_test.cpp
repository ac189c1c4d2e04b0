#include "daq/jack/interleaved_resampler.h"

#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

namespace oscilab::daq {
namespace {

constexpr double kRateIn = 48000.0;  // Hz, a sound card's
constexpr double kRateOut = 512.0;   // Hz, the analysis rate
constexpr double kPassbandEnd = 0.6;

TEST(InterleavedResampler, ReachesTwentyFourAnalysisSamplesFrom48kHz) {
  // docs/live.md: the impulse response reaches ±24 samples (47 ms) at 1e-6 of its peak.
  EXPECT_EQ(InterleavedResampler::measure_reach(kRateIn, kRateOut, kPassbandEnd), 24);
}

TEST(InterleavedResampler, OutputSampleKIsTheInputAtKOverTheOutputRateOnEveryChannel) {
  // Two sines of other frequencies and phases, one a channel, fed in JACK-sized periods: soxr
  // removes the group delay, so analysis sample k is each input at t = k / 512 s, and both
  // channels pass the same filter (the same delay).
  constexpr std::size_t kChannels = 2, kPeriod = 256;
  const double amplitude[kChannels] = {0.5, 0.25}, freq_hz[kChannels] = {9.0, 37.0},
               phase_rad[kChannels] = {0.3, -1.1};
  InterleavedResampler resampler;
  ASSERT_EQ(resampler.open(kRateIn, kRateOut, kChannels, kPassbandEnd, kPeriod), "");
  const auto frames = static_cast<std::size_t>(20.0 * kRateIn);  // 20 s
  std::vector<float> in(frames * kChannels);
  for (std::size_t n = 0; n < frames; ++n) {
    for (std::size_t c = 0; c < kChannels; ++c) {
      in[n * kChannels + c] =
          static_cast<float>(amplitude[c] * std::sin(2.0 * std::numbers::pi * freq_hz[c] *
                                                         static_cast<double>(n) / kRateIn +
                                                     phase_rad[c]));
    }
  }
  std::vector<double> out;
  const auto take = [&](std::size_t produced) {
    out.insert(out.end(), resampler.output(), resampler.output() + produced * kChannels);
  };
  for (std::size_t fed = 0; fed < frames;) {
    std::size_t used = 0;
    take(resampler.process(in.data() + fed * kChannels, std::min(kPeriod, frames - fed), used));
    fed += used;
  }
  while (const std::size_t produced = resampler.flush()) take(produced);
  const std::size_t samples = out.size() / kChannels;
  EXPECT_NEAR(static_cast<double>(samples), 20.0 * kRateOut, 1.0);  // N × rate_out / rate_in
  const auto reach = static_cast<std::size_t>(
      InterleavedResampler::measure_reach(kRateIn, kRateOut, kPassbandEnd));
  double worst = 0.0;
  for (std::size_t k = reach; k + reach < samples; ++k) {  // away from the silence at each end
    for (std::size_t c = 0; c < kChannels; ++c) {
      const double expected = amplitude[c] * std::sin(2.0 * std::numbers::pi * freq_hz[c] *
                                                          static_cast<double>(k) / kRateOut +
                                                      phase_rad[c]);
      worst = std::max(worst, std::abs(out[k * kChannels + c] - expected));
    }
  }
  // SOXR_HQ: 20-bit precision (~1e-6 of full scale), float input (~6e-8): 2e-6 as in the JACK
  // test of the same path.
  EXPECT_LT(worst, 2e-6);
}

TEST(InterleavedResampler, ClearStartsAfreshWithNothingHeldBack) {
  InterleavedResampler resampler;
  ASSERT_EQ(resampler.open(kRateIn, kRateOut, 1, kPassbandEnd, 256), "");
  std::vector<float> ones(256, 1.0f);
  std::size_t used = 0;
  for (int i = 0; i < 100; ++i) resampler.process(ones.data(), ones.size(), used);
  resampler.clear();
  EXPECT_EQ(resampler.flush(), 0u);  // nothing fed since the clear
}

}  // namespace
}  // namespace oscilab::daq
