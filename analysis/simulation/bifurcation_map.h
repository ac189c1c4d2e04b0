#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "analysis/common/job.h"
#include "analysis/model/model.h"

namespace oscilab::analysis {

/// Bifurcation map by time simulation (§5.2, Fig. 17): a stepped sine f = f0 sin ωt whose level
/// f0 steps through `levels`, simulated from rest at a well's equilibrium; in each hold the state
/// carries over from the previous level (as on the rig), the first periods are dropped, and z is
/// sampled once per forcing period at the same forcing phase (a Poincaré section) over the last
/// `sampled_periods` periods of the hold. A period-T response gives one point per level, a
/// period-2T response two, a chaotic one a smear.
///
/// Phase of the section: t = n T exactly (f = f0 sin ωt crosses zero upwards); the simulator's
/// steps land on these instants, so no sample is interpolated.
struct BifurcationMapOptions {
  double freq_hz = 9.0;
  /// Levels, N, in the order they are applied; empty: start_n, start_n + step_n, … ≤ end_n.
  std::vector<double> levels_n;
  double start_n = 0.1;
  double end_n = 3.7;
  double step_n = 0.05;
  bool positive_well = true;  // simulate the well around z₊*
  bool negative_well = true;  // and the one around z₋*
  /// Whole forcing periods per level (ramp included). The slowest transient of the paper's model
  /// near the flip decays like |μ|ⁿ with |μ| → 1; 200 periods (22 s at 9 Hz) leave
  /// 0.95²⁰⁰ ≈ 4e-5 of a disturbance at |μ| = 0.95.
  int hold_periods = 200;
  int ramp_periods = 5;      // C² amplitude ramp from the previous level (SteppedSineMotion)
  int sampled_periods = 32;  // K: sections recorded at the end of each hold
  /// Two sections closer than this belong to one point of the map (distinct_points), m.
  double cluster_tolerance_m = 1e-5;

  /// The levels actually applied.
  std::vector<double> resolved_levels() const;
  /// Throws InputError naming the option when the options make no sense.
  void validate() const;
};

/// One Poincaré section: a row of the map CSV.
struct BifurcationMapRow {
  double f0_n = 0.0;
  bool positive_well = true;
  double z_m = 0.0;
  int period = 0;  // index of the forcing period from the start of the run
};

/// What the sections of one level say.
struct BifurcationMapLevel {
  double f0_n = 0.0;
  bool positive_well = true;
  int distinct_points = 0;  // clusters of the sections at cluster_tolerance_m
  double spread_m = 0.0;    // max − min of the sections
  double z_min_m = 0.0;
  double z_max_m = 0.0;
};

struct BifurcationMap {
  JobStatus status = JobStatus::Ok;
  std::string message;  // why, whenever status != Ok
  BifurcationMapOptions options;
  std::vector<BifurcationMapRow> rows;      // by well (positive first), level, period
  std::vector<BifurcationMapLevel> levels;  // by well, level

  /// The levels of one well.
  std::vector<BifurcationMapLevel> levels_of(bool positive_well) const;
};

/// Runs one stepped-sine simulation per requested well. Progress is the fraction of simulated
/// time over all wells; cancellation is polled about once per simulated second and returns the
/// levels completed so far with JobStatus::Cancelled. Throws InputError for bad options or a
/// model without the requested well.
BifurcationMap bifurcation_map(const Model& model, const BifurcationMapOptions& options,
                               const ProgressFn& progress = {}, const CancelToken& cancel = {});

/// `f0_n,well,z_m,period`, one row per sampled period; `well` is `positive` or `negative`.
void write_bifurcation_map_csv(const BifurcationMap& map, std::ostream& out);
/// Throws InputError naming the file when it cannot be written.
void write_bifurcation_map_csv(const BifurcationMap& map, const std::string& path);

}  // namespace oscilab::analysis
