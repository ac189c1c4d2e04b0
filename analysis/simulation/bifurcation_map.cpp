#include "analysis/simulation/bifurcation_map.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <ostream>

#include "analysis/common/input_error.h"
#include "analysis/edc/well.h"
#include "analysis/simulation/stepped_sine_motion.h"
#include "analysis/simulation/time_simulator.h"

namespace oscilab::analysis {

std::vector<double> BifurcationMapOptions::resolved_levels() const {
  if (!levels_n.empty()) return levels_n;
  std::vector<double> out;
  // Level i = start + i step, up to end within 1e-9 of a step (rounding of the sum).
  for (int i = 0;; ++i) {
    const double f0 = start_n + i * step_n;
    if (f0 > end_n + 1e-9 * step_n) break;
    out.push_back(f0);
  }
  return out;
}

void BifurcationMapOptions::validate() const {
  if (!(freq_hz > 0.0) || !std::isfinite(freq_hz)) {
    throw InputError("bifurcation map: freq_hz: " + std::to_string(freq_hz) + " must be positive");
  }
  if (levels_n.empty()) {
    if (!(step_n > 0.0) || !(start_n >= 0.0) || !(end_n >= start_n)) {
      throw InputError("bifurcation map: levels: need 0 <= start <= end and step > 0 (start " +
                       std::to_string(start_n) + ", end " + std::to_string(end_n) + ", step " +
                       std::to_string(step_n) + ")");
    }
    if ((end_n - start_n) / step_n > 1e5) {
      throw InputError("bifurcation map: levels: more than 1e5 levels");
    }
  }
  for (double f0 : levels_n) {
    if (!std::isfinite(f0) || f0 < 0.0) {
      throw InputError("bifurcation map: levels: " + std::to_string(f0) + " N is not valid");
    }
  }
  if (!positive_well && !negative_well) throw InputError("bifurcation map: no well selected");
  if (ramp_periods < 1 || sampled_periods < 1 || hold_periods < ramp_periods + sampled_periods) {
    throw InputError(
        "bifurcation map: need 1 <= ramp_periods, 1 <= sampled_periods and "
        "ramp_periods + sampled_periods <= hold_periods");
  }
  if (!(cluster_tolerance_m > 0.0)) {
    throw InputError("bifurcation map: cluster_tolerance_m must be positive");
  }
  // One sample a period for every level of a well's run: bounded like any time simulation, and
  // checked here so that hbm --map refuses before it writes anything.
  const double level_count = levels_n.empty() ? std::floor((end_n - start_n) / step_n) + 1.0
                                              : static_cast<double>(levels_n.size());
  if (!(level_count * hold_periods < TimeSimulator::kMaxSamples)) {
    throw InputError("bifurcation map: " + std::to_string(static_cast<long>(level_count)) +
                     " levels of " + std::to_string(hold_periods) +
                     " periods are more samples than a time simulation holds");
  }
}

std::vector<BifurcationMapLevel> BifurcationMap::levels_of(bool positive_well) const {
  std::vector<BifurcationMapLevel> out;
  for (const BifurcationMapLevel& level : levels) {
    if (level.positive_well == positive_well) out.push_back(level);
  }
  return out;
}

namespace {

// Sorted sections form one cluster while successive gaps stay within the tolerance.
BifurcationMapLevel summarise(double f0_n, bool positive_well, std::vector<double> z,
                              double tolerance_m) {
  BifurcationMapLevel level;
  level.f0_n = f0_n;
  level.positive_well = positive_well;
  if (z.empty()) return level;
  std::sort(z.begin(), z.end());
  level.distinct_points = 1;
  for (std::size_t i = 1; i < z.size(); ++i) {
    if (z[i] - z[i - 1] > tolerance_m) ++level.distinct_points;
  }
  level.z_min_m = z.front();
  level.z_max_m = z.back();
  level.spread_m = z.back() - z.front();
  return level;
}

}  // namespace

BifurcationMap bifurcation_map(const Model& model, const BifurcationMapOptions& options,
                               const ProgressFn& progress, const CancelToken& cancel) {
  options.validate();
  BifurcationMap map;
  map.options = options;
  const std::vector<double> levels = options.resolved_levels();

  std::vector<bool> wells;
  if (options.positive_well) wells.push_back(true);
  if (options.negative_well) wells.push_back(false);

  const double period_s = 1.0 / options.freq_hz;
  SteppedSineSchedule schedule;
  schedule.frequency_hz = options.freq_hz;
  schedule.levels_n = levels;
  schedule.hold_s = options.hold_periods * period_s;
  schedule.ramp_s = options.ramp_periods * period_s;
  schedule.lead_in_s = 0.0;  // start at rest on the equilibrium: nothing to settle
  const SteppedSineMotion motion(schedule, model.mass_kg());
  const TimeSimulator simulator(model, {});

  for (std::size_t w = 0; w < wells.size(); ++w) {
    const bool positive = wells[w];
    TimeSimulator::Run run;
    run.z0_m = model.well(positive).z_m;
    run.duration_s = schedule.duration_s();
    run.sample_rate_hz = options.freq_hz;  // samples at t = n T: the Poincaré section
    ProgressFn well_progress;
    if (progress) {
      const double share = 1.0 / static_cast<double>(wells.size());
      well_progress = [&progress, share, w](double fraction) {
        progress((static_cast<double>(w) + fraction) * share);
      };
    }
    const TimeSimulator::Result result = simulator.simulate(motion, run, well_progress, cancel);

    // Level i holds periods [i P, (i + 1) P); its sections are the last K before the next level.
    const long hold = options.hold_periods, sampled = options.sampled_periods;
    for (std::size_t i = 0; i < levels.size(); ++i) {
      const long first = static_cast<long>(i + 1) * hold - sampled;
      const long last = static_cast<long>(i + 1) * hold - 1;
      if (last >= result.z_m.size()) break;  // cancelled or failed before this level ended
      std::vector<double> z;
      for (long n = first; n <= last; ++n) {
        map.rows.push_back({levels[i], positive, result.z_m[n], static_cast<int>(n)});
        z.push_back(result.z_m[n]);
      }
      map.levels.push_back(summarise(levels[i], positive, z, options.cluster_tolerance_m));
    }
    if (result.status == TimeSimulator::Status::Cancelled) {
      map.status = JobStatus::Cancelled;
      map.message = "cancelled";
      return map;
    }
    if (result.status != TimeSimulator::Status::Ok) {
      map.status = JobStatus::NumericalIssue;
      map.message = to_string(well_of(positive)) + " well: " + result.message;
      return map;
    }
  }
  if (progress) progress(1.0);
  return map;
}

void write_bifurcation_map_csv(const BifurcationMap& map, std::ostream& out) {
  out << "f0_n,well,z_m,period\n";
  out.precision(10);
  for (const BifurcationMapRow& row : map.rows) {
    out << row.f0_n << ',' << to_string(well_of(row.positive_well)) << ',' << row.z_m << ','
        << row.period << '\n';
  }
}

void write_bifurcation_map_csv(const BifurcationMap& map, const std::string& path) {
  std::ofstream file(path);
  if (!file) throw InputError(path + ": cannot write");
  write_bifurcation_map_csv(map, file);
  if (!file) throw InputError(path + ": write failed");
}

}  // namespace oscilab::analysis
