#pragma once

#include <vector>

#include "analysis/common/time_interval.h"
#include "analysis/edc/cycle_fit.h"

namespace oscilab::analysis {

/// Cuts a stream of samples into consecutive forcing cycles [t0 + nT, t0 + (n+1)T) and fits each
/// (CycleFit). The same object serves live and offline work: push() blocks of any size, in time
/// order; a cycle is fitted as soon as the first sample after its end arrives, so a live result
/// is ready one sample period after the cycle ends.
///
/// Memory is sized at construction (a little over one cycle of samples); push() does not grow
/// it. Not thread-safe: one producer thread.
class CycleAnalyzer {
 public:
  struct Options {
    CycleFitInput fit;            // frequency, mass, harmonics, channel quantities
    double sample_rate_hz = 512;  // sizes the buffer
    double t0_s = 0.0;            // start of the first cycle
  };
  explicit CycleAnalyzer(const Options& options);  // throws InputError on bad options

  /// Appends `count` samples; appends every cycle completed by them to `completed`.
  void push(const double* t_s, const double* base, const double* mass, int count,
            std::vector<CycleFit>& completed);

  /// Start time of the cycle being filled.
  double current_cycle_start_s() const { return cycle_start_s_; }

  /// Marks [start_s, end_s] as untrustworthy (a gap, non-finite or saturated samples, a
  /// discontinuity): every cycle whose samples (one beyond each end included) touch it is left
  /// out and counted. Call before pushing the samples it covers; intervals come in time order.
  /// Up to kMaxPendingExclusions are held without allocating; more are merged into the last.
  void exclude(double start_s, double end_s);
  /// Cycles left out because they touched an excluded interval.
  long excluded_cycles() const { return excluded_cycles_; }

  static constexpr std::size_t kMaxPendingExclusions = 64;

 private:
  Options options_;
  double period_s_;
  double cycle_start_s_;
  long cycle_index_ = 0;
  bool touches_exclusion(double start_s, double end_s);

  std::vector<double> t_, base_, mass_;  // samples from one before the cycle start onwards
  int size_ = 0;
  std::vector<TimeInterval> exclusions_;  // pending, in time order; capacity reserved
  long excluded_cycles_ = 0;
};

}  // namespace oscilab::analysis
