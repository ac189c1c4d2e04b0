#include "analysis/simulation/stepped_sine_run.h"

#include <cmath>

namespace oscilab::analysis {

SteppedSineRun simulate_stepped_sine(const TimeSimulator& simulator,
                                     const SteppedSineMotion& motion, double z0_m,
                                     double sample_rate_hz, const ProgressFn& progress,
                                     const CancelToken& cancel) {
  const SteppedSineSchedule& schedule = motion.schedule();
  TimeSimulator::Run run;
  run.z0_m = z0_m;
  run.duration_s = schedule.duration_s();
  run.sample_rate_hz = sample_rate_hz;

  SteppedSineRun out;
  for (std::size_t i = 0; i < schedule.levels_n.size(); ++i) {
    const double start = schedule.steady_start_s(i), end = schedule.steady_end_s(i);
    const double settled = 0.5 * (start + end);
    // Cycle boundaries n/ν inside [settled, end]; the small margin keeps a boundary that falls on
    // `end` up to rounding inside the level.
    const auto first = static_cast<long>(std::ceil(settled * schedule.frequency_hz));
    const auto last = static_cast<long>(std::floor(end * schedule.frequency_hz * (1 - 1e-12)));
    LevelEnergy level;
    level.f0_n = schedule.levels_n[i];
    level.cycles = static_cast<int>(std::max(0L, last - first));
    level.start_s = static_cast<double>(first) / schedule.frequency_hz;
    level.end_s = static_cast<double>(last) / schedule.frequency_hz;
    if (level.cycles > 0) {
      run.probe_times_s.push_back(level.start_s);
      run.probe_times_s.push_back(level.end_s);
    }
    out.levels.push_back(level);
  }

  out.samples = simulator.simulate(motion, run, progress, cancel);
  Eigen::Index p = 0;
  for (LevelEnergy& level : out.levels) {
    if (level.cycles == 0) continue;
    if (p + 1 >= out.samples.probe_dissipated_j.size()) {  // cancelled before this level
      level.cycles = 0;
      continue;
    }
    level.edc_j =
        (out.samples.probe_dissipated_j[p + 1] - out.samples.probe_dissipated_j[p]) / level.cycles;
    p += 2;
  }
  return out;
}

}  // namespace oscilab::analysis
