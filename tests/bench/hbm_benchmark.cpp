// Speed of harmonic balance with continuation: one branch of the paper's model
// (positive well, 9 Hz, H = 7, f0 0.1 → 3.7 N) with Floquet stability at every point (target
// ≤ 50 ms) and without (≤ 5 ms), and one identification cost evaluation: the EDC at the 26 levels
// 0.2 → 2.7 N of both wells (≤ 5 ms). Counters: points per branch and time per point. Google
// Benchmark reports medians over repetitions; nothing here asserts a speed.
#include <benchmark/benchmark.h>

#include "analysis/hbm/continuation.h"
#include "analysis/hbm/level_response.h"
#include "analysis/model/reference_models.h"

namespace {

using namespace oscilab::analysis;

void BM_PaperBranch(benchmark::State& state) {
  const bool stability = state.range(0) == 1;
  const Model model = paper_model();
  ContinuationOptions options;
  options.freq_hz = 9.0;
  options.start = 0.1;
  options.end = 3.7;
  options.hbm.harmonics = 7;
  options.stability = stability;
  std::size_t points = 0;
  for (auto _ : state) {
    const Branch branch = continue_branch(model, options);
    points = branch.points.size();
    benchmark::DoNotOptimize(branch.points.data());
  }
  state.counters["points"] = static_cast<double>(points);
  state.counters["time_per_point"] =
      benchmark::Counter(static_cast<double>(points) * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.SetLabel(stability ? "with Floquet stability" : "without stability");
}
BENCHMARK(BM_PaperBranch)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_IdentificationCost(benchmark::State& state) {
  const Model model = paper_model();
  std::vector<double> levels;
  for (int i = 0; i < 26; ++i) levels.push_back(0.2 + 0.1 * i);
  HbmOptions hbm;
  hbm.harmonics = 7;
  hbm.samples = static_cast<int>(state.range(0));  // 0: the default N = 16H = 128
  for (auto _ : state) {
    double sum = 0.0;
    for (bool positive : {true, false}) {
      const LevelResponse response = level_response(model, 9.0, positive, levels, hbm);
      for (double edc : response.edc_j) sum += edc;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetLabel("both wells, 26 levels, H = 7, N = " + std::to_string(hbm.resolved_samples()));
}
BENCHMARK(BM_IdentificationCost)->Arg(0)->Arg(64)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
