#include "daq/live/live_edc.h"

#include <algorithm>
#include <chrono>

#include <gtest/gtest.h>

#include "analysis/model/reference_models.h"
#include "analysis/pipeline/offline_analysis.h"
#include "daq/recording/measurement_mapping.h"
#include "daq/rig/virtual_rig.h"

namespace oscilab::daq {
namespace {

using std::chrono::milliseconds;
using std::chrono::steady_clock;

constexpr int kBlockRows = 16;

// The rig's two levels fed in live blocks on a made-up clock: each sample "arrives" 1 ms after
// the one before it, and each block is published 100 ms after it arrived.
struct LiveRun {
  analysis::RecordAnalysis offline;
  LiveEdc edc;
  AcquisitionStatus status;
};

void run_live(LiveRun& run, std::uint64_t seed, std::size_t kept_cycles = LiveEdc::kKeptCycles) {
  analysis::SteppedSineSchedule schedule;
  schedule.levels_n = {0.5, 1.3};
  RigSpec spec;
  spec.seed = seed;
  const RigRecording rig = record_stepped_sine(analysis::paper_model(), schedule, spec);
  const analysis::MeasurementChannels channels = measurement_channels(rig.recording);
  run.offline = analysis::analyze_record(channels, analysis::PipelineSettings{});
  analysis::StreamSetup stream = run.offline.setup;
  stream.level_windows.clear();  // the pipelines take them from the sidecar's excitation
  run.edc.configure(analysis::PipelineSettings{}, stream, rig.recording.sidecar.excitation);
  run.edc.keep_cycles(kept_cycles);
  run.edc.start(run.offline.setup.excitation_freq_hz, 0.0);
  const auto n = static_cast<std::uint64_t>(channels.base.size());
  for (std::uint64_t first = 0; first < n; first += kBlockRows) {
    const int rows = static_cast<int>(std::min<std::uint64_t>(kBlockRows, n - first));
    const steady_clock::time_point delivered =
        steady_clock::time_point{} + milliseconds(static_cast<std::int64_t>(first));
    run.edc.note_arrival(first, first + static_cast<std::uint64_t>(rows), delivered);
    run.edc.push(first, channels.base.data() + first, channels.mass.data() + first, rows);
    run.edc.publish(delivered + milliseconds(100), run.status);
  }
  run.edc.finish();
  run.edc.publish_finished(run.status);
}

TEST(LiveEdc, PublishesTheLevelsOfTheOfflineAnalysis) {
  LiveRun run;
  run_live(run, 7);
  const auto& levels = run.edc.levels();
  ASSERT_EQ(levels.size(), run.offline.levels.size());
  EXPECT_EQ(run.status.levels, levels.size());
  for (std::size_t k = 0; k < levels.size(); ++k) {
    // The same engine on the same samples; only the block timestamps' rounding differs.
    EXPECT_NEAR(levels[k].edc_mean_j, run.offline.levels[k].edc_mean_j,
                1e-9 * run.offline.levels[k].edc_mean_j);
    EXPECT_EQ(levels[k].cycles, run.offline.levels[k].cycles);
  }
  EXPECT_FALSE(run.edc.current_level().has_value());  // finished
  EXPECT_EQ(run.status.cycles, static_cast<long>(run.edc.cycles().size()));
  EXPECT_EQ(run.edc.cycle_count(), run.offline.cycles.size());
}

// A day-long stream fits 800 000 cycles: only the newest are kept, the count goes on, and the
// levels (what is measured) do not depend on how many are kept.
TEST(LiveEdc, KeepsTheNewestCyclesOnlyAndCountsThemAll) {
  LiveRun all, newest;
  run_live(all, 7);
  run_live(newest, 7, 40);
  ASSERT_GT(all.edc.cycles().size(), 100u);
  EXPECT_EQ(newest.edc.cycles().size(), 40u);
  EXPECT_EQ(newest.edc.cycle_count(), all.edc.cycle_count());
  EXPECT_EQ(newest.status.cycles, all.status.cycles);
  const std::size_t skipped = all.edc.cycles().size() - 40;
  for (std::size_t k = 0; k < 40; ++k) {
    EXPECT_EQ(newest.edc.cycles()[k].start_s, all.edc.cycles()[skipped + k].start_s) << k;
    EXPECT_EQ(newest.edc.cycles()[k].edc_j, all.edc.cycles()[skipped + k].edc_j) << k;
  }
  ASSERT_EQ(newest.edc.levels().size(), all.edc.levels().size());
  for (std::size_t k = 0; k < all.edc.levels().size(); ++k) {
    EXPECT_EQ(newest.edc.levels()[k].edc_mean_j, all.edc.levels()[k].edc_mean_j) << k;
  }
}

TEST(LiveEdc, EachCyclesLatencyRunsFromTheArrivalOfItsFirstSample) {
  LiveRun run;
  run_live(run, 8);
  const auto& cycles = run.edc.cycles();
  const auto& latencies = run.edc.latencies_s();
  ASSERT_FALSE(cycles.empty());
  ASSERT_EQ(latencies.size(), cycles.size());  // every cycle's first block was still known
  const double rate_hz = run.offline.setup.sample_rate_hz;
  for (std::size_t k = 0; k < cycles.size(); ++k) {
    // A cycle's EDC comes no earlier than its last sample: on the made-up clock that is its
    // length in samples (1 ms each) after its first sample's block, minus the block's span,
    // plus the 100 ms to publishing.
    const double cycle_samples = (cycles[k].end_s - cycles[k].start_s) * rate_hz;
    EXPECT_GE(latencies[k], 0.1 + 1e-3 * (cycle_samples - kBlockRows - 1)) << "cycle " << k;
  }
  EXPECT_DOUBLE_EQ(run.status.edc_latency_max_s,
                   *std::max_element(latencies.begin(), latencies.end()));
}

}  // namespace
}  // namespace oscilab::daq
