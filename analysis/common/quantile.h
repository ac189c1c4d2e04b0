#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

namespace oscilab {

/// The q-quantiles (0 ≤ q ≤ 1) of `values`, each interpolated linearly between the order
/// statistics at position q (n − 1) (Hyndman & Fan 1996, definition 7, the default of R and
/// NumPy): the minimum at q = 0, the median at 0.5, the maximum at 1; 0 for no values. In the
/// order of `qs`. O(n) per quantile on one copy: the copy is partially ordered
/// (std::nth_element), never sorted, each selection starting where the one below it ended.
inline std::vector<double> quantiles(std::vector<double> values, const std::vector<double>& qs) {
  std::vector<double> out(qs.size(), 0.0);
  if (values.empty()) return out;
  std::vector<std::size_t> ascending(qs.size());
  for (std::size_t i = 0; i < qs.size(); ++i) ascending[i] = i;
  std::sort(ascending.begin(), ascending.end(),
            [&qs](std::size_t a, std::size_t b) { return qs[a] < qs[b]; });
  // Every value before `from` is at most every value from it on.
  auto from = values.begin();
  for (const std::size_t i : ascending) {
    const double position = std::clamp(qs[i], 0.0, 1.0) * static_cast<double>(values.size() - 1);
    const auto below = static_cast<std::size_t>(std::floor(position));
    const auto nth = values.begin() + static_cast<std::ptrdiff_t>(below);
    if (nth >= from) std::nth_element(from, nth, values.end());
    from = nth;
    const double low = *nth;
    if (below + 1 >= values.size()) {
      out[i] = low;
      continue;
    }
    const double high = *std::min_element(nth + 1, values.end());  // the next order statistic
    out[i] = low + (position - static_cast<double>(below)) * (high - low);
  }
  return out;
}

/// One q-quantile of `values`, as quantiles() gives it.
inline double quantile(std::vector<double> values, double q) {
  return quantiles(std::move(values), {q}).front();
}

/// The median: quantile(values, 0.5), the mean of the middle two for an even count.
inline double median(std::vector<double> values) { return quantile(std::move(values), 0.5); }

}  // namespace oscilab
