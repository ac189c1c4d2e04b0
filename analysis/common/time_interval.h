#pragma once

namespace oscilab::analysis {

/// A closed stretch of time [start_s, end_s] of a record or a stream; start_s == end_s marks an
/// instant (a discontinuity between two samples).
struct TimeInterval {
  double start_s = 0.0;
  double end_s = 0.0;
  bool overlaps(double from_s, double to_s) const { return start_s <= to_s && end_s >= from_s; }
};

}  // namespace oscilab::analysis
