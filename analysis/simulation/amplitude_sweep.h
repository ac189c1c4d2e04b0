#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "analysis/common/job.h"
#include "analysis/model/model.h"

namespace oscilab::analysis {

/// The amplitude sweep of §4.2 (Fig. 12) by time integration: f0 ramps slowly up from 0 to
/// `f0_max_n` and back down at fixed frequency, from rest at a well's equilibrium. Where the
/// harmonic-balance branch folds, the response has nowhere nearby to go and jumps: up at the
/// first fold on the way up, down at the other fold on the way down (hysteresis).
struct AmplitudeSweepOptions {
  double freq_hz = 1.0;
  double f0_max_n = 2.0;
  /// Duration of each direction, s. A slow sweep passes a fold late, by ≈ C rate^(2/3) (slow
  /// passage through a saddle-node): with the eq. (14) example at 400 s per direction
  /// (0.005 N/s) the jumps come 0.020 N (up) and 0.024 N (down) after the folds, which are
  /// 0.032 N apart; halving the rate shrinks that by ≈ 1.6 (docs/hbm.md §8).
  double up_s = 400.0;
  double down_s = 400.0;
  bool positive_well = true;
  /// Samples per forcing period used to measure each period's amplitude (max − min) / 2.
  int samples_per_period = 64;

  /// Throws InputError naming the option when the options make no sense.
  void validate() const;
};

/// One forcing period of the sweep.
struct AmplitudeSweepPeriod {
  double t_s = 0.0;    // start of the period
  double f0_n = 0.0;   // f0 at the middle of the period
  bool up = true;      // on the way up
  double amp_m = 0.0;  // (max z − min z) / 2 over the period
};

/// The largest period-to-period change of the amplitude in one direction: the middle of the jump,
/// which takes several periods (amp_before_m and amp_after_m are the two periods around it, not
/// the ends of the jump).
struct AmplitudeSweepJump {
  bool up = true;
  double f0_n = 0.0;  // f0 between the two periods
  double amp_before_m = 0.0;
  double amp_after_m = 0.0;
};

struct AmplitudeSweep {
  JobStatus status = JobStatus::Ok;
  std::string message;  // why, whenever status != Ok
  AmplitudeSweepOptions options;
  std::vector<AmplitudeSweepPeriod> periods;
  AmplitudeSweepJump jump_up, jump_down;
};

/// Simulates the sweep (TimeSimulator, default tolerances). Progress is the fraction of simulated
/// time; cancellation returns the periods so far with JobStatus::Cancelled. Throws InputError for
/// bad options or a model without the requested well.
AmplitudeSweep amplitude_sweep(const Model& model, const AmplitudeSweepOptions& options,
                               const ProgressFn& progress = {}, const CancelToken& cancel = {});

/// `f0_n,direction,amp_m,t_s`, one row per forcing period; `direction` is `up` or `down`.
void write_amplitude_sweep_csv(const AmplitudeSweep& sweep, std::ostream& out);
/// Throws InputError naming the file when it cannot be written.
void write_amplitude_sweep_csv(const AmplitudeSweep& sweep, const std::string& path);

}  // namespace oscilab::analysis
