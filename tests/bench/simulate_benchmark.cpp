// Speed of the time simulation (target: ≥ 200× real time on one core for the default stepped-sine
// test of 262.5 s with its 512 Hz output). The counter `x_realtime` is simulated seconds per
// wall-clock second; Google Benchmark reports the median over repetitions.
#include <benchmark/benchmark.h>

#include "analysis/edc/well.h"
#include "analysis/model/reference_models.h"
#include "analysis/simulation/stepped_sine_run.h"

namespace {

using namespace oscilab::analysis;

SteppedSineSchedule default_test() {  // what `oscilab-cli simulate` runs by default
  SteppedSineSchedule schedule;
  for (int i = 0; i < 26; ++i) schedule.levels_n.push_back(0.2 + 0.1 * i);
  return schedule;
}

void BM_SimulateSteppedSine(benchmark::State& state) {
  const bool positive = state.range(0) == 1;
  const Model model = paper_model();
  const SteppedSineMotion motion(default_test(), model.mass_kg());
  const TimeSimulator simulator(model, {});
  const double z0 = model.well(positive).z_m;
  long evaluations = 0;
  for (auto _ : state) {
    const SteppedSineRun run = simulate_stepped_sine(simulator, motion, z0, 512.0);
    evaluations = run.samples.rhs_evaluations;
    benchmark::DoNotOptimize(run.levels.data());
  }
  state.counters["x_realtime"] = benchmark::Counter(
      motion.duration_s() * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["rhs_evals"] = static_cast<double>(evaluations);
  state.SetLabel(to_string(well_of(positive)) + " well, " + std::to_string(motion.duration_s()) +
                 " s simulated");
}
BENCHMARK(BM_SimulateSteppedSine)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
