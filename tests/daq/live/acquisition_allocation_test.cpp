// The acquisition's per-block path allocates nothing once it is warm: a clean block is checked,
// calibrated, integrated, published and kept for display with the memory it already has. This
// binary replaces the global operator new to count the allocations of the acquisition thread (any
// thread but the test's and the source's) while a steady stream passes.
#include <atomic>
#include <cmath>
#include <thread>

#include <gtest/gtest.h>

#include "daq/live/acquisition.h"
#include "tests/allocation_counter.h"

namespace oscilab::daq {
namespace {

using oscilab::testing::allocation_counter;
std::atomic<std::thread::id> source_thread;

constexpr double kRateHz = 512.0;
constexpr int kRows = 16;

// A table at 9 Hz and a mass moving with it: base acceleration (m/s²) and mass position (m).
Sidecar steady_layout() {
  Sidecar s;
  s.sample_rate_hz = kRateHz;
  s.mass_kg = 0.26;
  ChannelInfo base;
  base.name = "base_acc";
  base.role = ChannelRole::Base;
  base.quantity = Quantity::Acceleration;
  base.unit = "m/s^2";
  base.range = std::pair{-500.0, 500.0};
  ChannelInfo mass = base;
  mass.name = "y";
  mass.role = ChannelRole::Mass;
  mass.quantity = Quantity::Displacement;
  mass.unit = "m";
  mass.range = std::pair{-1.0, 1.0};
  s.channels = {base, mass};
  return s;
}

// Delivers `warm_up` blocks, waits for the test's go, delivers `measured` more, then waits to be
// stopped (so that the end of the stream falls outside the count).
class SteadySource final : public SampleSource {
 public:
  SteadySource(std::uint64_t warm_up, std::uint64_t measured)
      : warm_up_(warm_up), measured_(measured) {
    set_layout(steady_layout());
  }
  ~SteadySource() override { stop(); }
  int max_block_rows() const override { return kRows; }
  std::string describe() const override { return "steady"; }
  std::atomic<bool> go{false};

 private:
  void run() override {
    source_thread = std::this_thread::get_id();
    for (std::uint64_t k = 0; k < warm_up_ + measured_; ++k) {
      while (k == warm_up_ && !go.load() && !stop_requested()) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
      RawBlock* block = begin_block(true);
      if (block == nullptr) return;
      block->sequence = k;
      block->first_sample = k * kRows;
      block->rows = kRows;
      block->channels = 2;
      for (int r = 0; r < kRows; ++r) {
        const double t = static_cast<double>(k * kRows + static_cast<std::uint64_t>(r)) / kRateHz;
        const double w = 2 * 3.14159265358979 * 9.0;
        block->values[static_cast<std::size_t>(2 * r)] = -w * w * 1e-3 * std::sin(w * t);
        block->values[static_cast<std::size_t>(2 * r + 1)] = 4e-3 * std::sin(w * t + 0.5);
      }
      end_block(*block);
    }
    while (!stop_requested()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  std::uint64_t warm_up_, measured_;
};

void wait_for_samples(const Acquisition& acquisition, std::uint64_t samples) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (acquisition.status().samples < samples && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ASSERT_EQ(acquisition.status().samples, samples);
}

// Derived signals (with their 2 s of filter latency), the sample checks, alarm limits and the
// ten-minute history ring all run; the EDC pipeline is off (the layout names no excitation
// frequency): a cycle's harmonic fit is per cycle, not per block, and allocates its own work.
TEST(AcquisitionAllocations, ACleanBlockAllocatesNothingOnceWarm) {
  const std::uint64_t warm_up = 256, measured = 2048;  // 8 s, then 64 s of stream
  auto owned = std::make_unique<SteadySource>(warm_up, measured);
  SteadySource* source = owned.get();
  AcquisitionOptions options;
  options.alarms.max_abs_z_m = 1.0;
  options.alarms.max_abs_base_m = 1.0;
  options.alarms.max_abs_force_n = 1e3;
  Acquisition acquisition(std::move(owned), options);
  acquisition.start();
  wait_for_samples(acquisition, warm_up * kRows);
  allocation_counter.start(std::this_thread::get_id(), source_thread.load());
  source->go.store(true);
  wait_for_samples(acquisition, (warm_up + measured) * kRows);
  const std::uint64_t seen = allocation_counter.stop();
  acquisition.stop();
  EXPECT_EQ(seen, 0u) << "allocations on the acquisition thread over " << measured
                      << " blocks, the first by \"" << allocation_counter.first_thread_name << "\"";
  // The chain did its work meanwhile: derived z in the history, no fault, no alarm.
  TraceHistory h;
  acquisition.history(60.0, 70.0, 100000, h);
  ASSERT_FALSE(h.z_m.empty());
  EXPECT_TRUE(std::isfinite(h.z_m[h.z_m.size() / 2]));
  EXPECT_EQ(acquisition.status().alarms, 0u);
  EXPECT_EQ(acquisition.status().non_finite_samples + acquisition.status().saturated_samples, 0u);
}

// The counter is live: the same chain with a limit on z that the motion crosses once the derived
// signals start (2 × 2 s of filter to fill, inside the counted stretch) allocates the alarm's
// text and event, so a zero above is not a counter that never counts.
TEST(AcquisitionAllocations, TheCounterSeesTheAllocationsOfAnAlarm) {
  auto owned = std::make_unique<SteadySource>(64, 256);  // 2 s, then 8 s
  SteadySource* source = owned.get();
  AcquisitionOptions options;
  options.alarms.max_abs_z_m = 1e-3;  // |z| = |y − b| reaches about 3.5 mm
  Acquisition acquisition(std::move(owned), options);
  acquisition.start();
  wait_for_samples(acquisition, 64 * kRows);
  EXPECT_EQ(acquisition.status().alarms, 0u);
  allocation_counter.start(std::this_thread::get_id(), source_thread.load());
  source->go.store(true);
  wait_for_samples(acquisition, 320 * kRows);
  const std::uint64_t seen = allocation_counter.stop();
  acquisition.stop();
  EXPECT_GT(seen, 0u);
  EXPECT_EQ(acquisition.status().alarms, 1u);
}

}  // namespace
}  // namespace oscilab::daq
