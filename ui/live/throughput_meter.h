#pragma once

#include <cstdint>
#include <deque>
#include <utility>

namespace oscilab::ui {

/// Samples per second of wall time, from the sample counter read at display rate: a running
/// figure over about the last `span_s`.
class ThroughputMeter {
 public:
  explicit ThroughputMeter(double span_s = 1.0) : span_s_(span_s) {}
  void reset() { readings_.clear(); }
  void add(double wall_s, std::uint64_t samples);
  /// Samples per second; 0 before two readings span a tenth of a second.
  double samples_per_s() const;

 private:
  double span_s_;
  std::deque<std::pair<double, std::uint64_t>> readings_;
};

}  // namespace oscilab::ui
