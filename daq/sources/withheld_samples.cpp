#include "daq/sources/withheld_samples.h"

#include <algorithm>

namespace oscilab::daq {

void WithheldSamples::add(std::uint64_t from, std::uint64_t to) {
  if (to <= from) return;
  for (auto& interval : intervals_) {  // overlapping or touching: merged
    if (from <= interval.second && to >= interval.first) {
      interval.first = std::min(interval.first, from);
      interval.second = std::max(interval.second, to);
      return;
    }
  }
  if (intervals_.size() == kMaxIntervals) {  // bounded: the last one grows to cover this too
    intervals_.back().second = std::max(intervals_.back().second, to);
    return;
  }
  intervals_.emplace_back(from, to);
}

bool WithheldSamples::contains(std::uint64_t index) const {
  for (const auto& interval : intervals_) {
    if (index >= interval.first && index < interval.second) return true;
  }
  return false;
}

void WithheldSamples::drop_before(std::uint64_t end) {
  intervals_.erase(std::remove_if(intervals_.begin(), intervals_.end(),
                                  [end](const auto& interval) { return interval.second <= end; }),
                   intervals_.end());
}

}  // namespace oscilab::daq
