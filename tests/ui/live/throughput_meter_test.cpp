// Samples per wall-clock second from the sample counter.
#include "ui/live/throughput_meter.h"

#include <cstdint>

#include <gtest/gtest.h>

namespace oscilab::ui {
namespace {

TEST(ThroughputMeter, MeasuresSamplesPerWallSecond) {
  ThroughputMeter meter(1.0);
  EXPECT_EQ(meter.samples_per_s(), 0.0);
  for (int i = 0; i <= 30; ++i) meter.add(0.1 * i, static_cast<std::uint64_t>(5120 * i));
  EXPECT_NEAR(meter.samples_per_s(), 51200.0, 1e-6);  // 100× of 512 Hz
  meter.add(3.1, 0);                                  // a new stream: starts over
  EXPECT_EQ(meter.samples_per_s(), 0.0);
}

}  // namespace
}  // namespace oscilab::ui
