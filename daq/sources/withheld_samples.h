#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace oscilab::daq {

/// The stretches of a stream's sample clock a source must not hand on (what a fault or the
/// resampler's start and end reach), as half-open intervals [from, to) of sample indices.
/// Overlapping or touching intervals merge; at most kMaxIntervals are kept, beyond which the
/// last one grows to cover the new one too (more is withheld, never less).
///
/// Thread-safety: one thread. Allocates only at construction.
class WithheldSamples {
 public:
  static constexpr std::size_t kMaxIntervals = 256;

  WithheldSamples() { intervals_.reserve(kMaxIntervals); }

  /// Withholds [from, to); nothing when to <= from.
  void add(std::uint64_t from, std::uint64_t to);
  bool contains(std::uint64_t index) const;
  /// Forgets the intervals wholly before `end` (the samples up to there are done with).
  void drop_before(std::uint64_t end);
  void clear() { intervals_.clear(); }
  const std::vector<std::pair<std::uint64_t, std::uint64_t>>& intervals() const {
    return intervals_;
  }

 private:
  std::vector<std::pair<std::uint64_t, std::uint64_t>> intervals_;
};

}  // namespace oscilab::daq
