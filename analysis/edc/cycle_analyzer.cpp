#include "analysis/edc/cycle_analyzer.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {

CycleAnalyzer::CycleAnalyzer(const Options& options)
    : options_(options), cycle_start_s_(options.t0_s) {
  if (!(options.fit.freq_hz > 0) || !std::isfinite(options.fit.freq_hz)) {
    throw InputError("cycle analysis: excitation frequency " + std::to_string(options.fit.freq_hz) +
                     " Hz must be positive");
  }
  if (!(options.sample_rate_hz > 0)) {
    throw InputError("cycle analysis: sample rate must be positive");
  }
  period_s_ = 1.0 / options.fit.freq_hz;
  // A cycle with a gap (over 10 % of its samples missing) is not fitted.
  options_.fit.min_samples = static_cast<int>(std::floor(0.9 * period_s_ * options.sample_rate_hz));
  // One cycle of samples, plus one before and one after, plus slack for timestamp jitter.
  const auto capacity =
      static_cast<std::size_t>(std::ceil(period_s_ * options.sample_rate_hz * 1.25)) + 8;
  t_.resize(capacity);
  base_.resize(capacity);
  mass_.resize(capacity);
  exclusions_.reserve(kMaxPendingExclusions);
}

void CycleAnalyzer::exclude(double start_s, double end_s) {
  if (!(end_s >= start_s)) return;
  if (!exclusions_.empty() && start_s <= exclusions_.back().end_s) {
    exclusions_.back().end_s = std::max(exclusions_.back().end_s, end_s);
    return;
  }
  if (exclusions_.size() == kMaxPendingExclusions) {
    exclusions_.back().end_s = end_s;  // merged: a longer exclusion, never a missed one
    return;
  }
  exclusions_.push_back({start_s, end_s});
}

bool CycleAnalyzer::touches_exclusion(double start_s, double end_s) {
  // The fit uses one sample beyond each end of the window (cycle_fit.h).
  const double dt = 1.0 / options_.sample_rate_hz;
  std::size_t expired = 0;
  while (expired < exclusions_.size() && exclusions_[expired].end_s < start_s - dt) ++expired;
  if (expired > 0) exclusions_.erase(exclusions_.begin(), exclusions_.begin() + expired);
  for (const TimeInterval& interval : exclusions_) {
    if (interval.overlaps(start_s - dt, end_s + dt)) return true;
  }
  return false;
}

void CycleAnalyzer::push(const double* t_s, const double* base, const double* mass, int count,
                         std::vector<CycleFit>& completed) {
  for (int i = 0; i < count; ++i) {
    if (t_s[i] < cycle_start_s_ && size_ > 0) {
      // Still before the first cycle: keep only the latest sample (the one before the start).
      size_ = 0;
    }
    if (static_cast<std::size_t>(size_) == t_.size()) {
      // More samples than one cycle can hold (timestamps far off the nominal rate): drop the
      // oldest half rather than grow; the cycle fails its sample count and is skipped.
      const int keep = size_ / 2;
      std::copy(t_.begin() + (size_ - keep), t_.begin() + size_, t_.begin());
      std::copy(base_.begin() + (size_ - keep), base_.begin() + size_, base_.begin());
      std::copy(mass_.begin() + (size_ - keep), mass_.begin() + size_, mass_.begin());
      size_ = keep;
    }
    t_[size_] = t_s[i];
    base_[size_] = base[i];
    mass_[size_] = mass[i];
    ++size_;
    while (t_s[i] >= cycle_start_s_ + period_s_) {
      CycleFit fit;
      if (touches_exclusion(cycle_start_s_, cycle_start_s_ + period_s_)) {
        ++excluded_cycles_;
      } else if (fit_cycle(options_.fit, cycle_start_s_, t_.data(), base_.data(), mass_.data(),
                           size_, fit)) {
        completed.push_back(std::move(fit));
      }
      ++cycle_index_;
      cycle_start_s_ = options_.t0_s + static_cast<double>(cycle_index_) * period_s_;
      // Keep the samples from the last one before the new start onwards.
      int first = 0;
      while (first + 1 < size_ && t_[first + 1] < cycle_start_s_) ++first;
      if (first > 0) {
        std::copy(t_.begin() + first, t_.begin() + size_, t_.begin());
        std::copy(base_.begin() + first, base_.begin() + size_, base_.begin());
        std::copy(mass_.begin() + first, mass_.begin() + size_, mass_.begin());
        size_ -= first;
      }
    }
  }
}

}  // namespace oscilab::analysis
