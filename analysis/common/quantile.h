#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

namespace oscilab {

/// The q-quantile (0 ≤ q ≤ 1) of `values`, interpolated linearly between the order statistics
/// at position q (n − 1) (Hyndman & Fan 1996, definition 7, the default of R and NumPy): the
/// minimum at q = 0, the median at 0.5, the maximum at 1. 0 for no values. O(n): the copy is
/// partially ordered (std::nth_element), not sorted.
inline double quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  const double position = std::clamp(q, 0.0, 1.0) * static_cast<double>(values.size() - 1);
  const auto below = static_cast<std::size_t>(std::floor(position));
  const auto nth = values.begin() + static_cast<std::ptrdiff_t>(below);
  std::nth_element(values.begin(), nth, values.end());
  const double low = *nth;
  if (below + 1 >= values.size()) return low;
  const double high = *std::min_element(nth + 1, values.end());  // the next order statistic
  return low + (position - static_cast<double>(below)) * (high - low);
}

/// The median: quantile(values, 0.5), the mean of the middle two for an even count.
inline double median(std::vector<double> values) { return quantile(std::move(values), 0.5); }

}  // namespace oscilab
