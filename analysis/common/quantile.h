#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace oscilab {

namespace detail {

/// The order statistics of rank k and k + 1 (0-based, k + 1 < n) of `values`, which it reorders.
/// For large n the ranks are first bracketed from a sample of about 4 000 values (drawn by a
/// fixed pseudo-random sequence, so that a periodic signal cannot alias with it): one pass keeps
/// the values between the sample's bracket and counts those below, and the selection runs on
/// the kept few per cent. A bracket that misses (a chance of about 1e-6) falls back to the
/// whole array, so the result is always exact.
inline std::pair<double, double> order_statistics_at(std::vector<double>& values, std::size_t k) {
  const std::size_t n = values.size();
  const auto select = [k](std::vector<double>& v, std::size_t offset) {
    const auto nth = v.begin() + static_cast<std::ptrdiff_t>(k - offset);
    std::nth_element(v.begin(), nth, v.end());
    return std::make_pair(*nth, *std::min_element(nth + 1, v.end()));
  };
  constexpr std::size_t kSampled = 4096;
  if (n < 16 * kSampled) return select(values, 0);
  std::vector<double> sample(kSampled);
  std::uint64_t state = 0x9E3779B97F4A7C15ull;  // xorshift64
  for (double& s : sample) {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    s = values[static_cast<std::size_t>(state % n)];
  }
  std::sort(sample.begin(), sample.end());
  // The ranks' place in the sample, ± 6 binomial standard deviations (and 2 places).
  const double q = (static_cast<double>(k) + 0.5) / static_cast<double>(n);
  const double centre = q * kSampled;
  const double spread = 6.0 * std::sqrt(kSampled * q * (1.0 - q)) + 2.0;
  const double lowest = -std::numeric_limits<double>::infinity();
  const double highest = std::numeric_limits<double>::infinity();
  const auto place = [&](double x) { return static_cast<std::ptrdiff_t>(std::floor(x)); };
  const std::ptrdiff_t lo_place = place(centre - spread), hi_place = place(centre + spread) + 1;
  const double lo = lo_place < 0 ? lowest : sample[static_cast<std::size_t>(lo_place)];
  const double hi = hi_place >= static_cast<std::ptrdiff_t>(kSampled)
                        ? highest
                        : sample[static_cast<std::size_t>(hi_place)];
  std::vector<double> kept;
  kept.reserve(static_cast<std::size_t>(4.0 * spread / kSampled * static_cast<double>(n)) + 16);
  std::size_t below = 0;
  for (const double v : values) {
    if (v < lo) {
      ++below;
    } else if (v <= hi) {
      kept.push_back(v);
    }
  }
  // Sorted, the values are: those below lo, then the kept ones, then those above hi.
  if (below <= k && k + 1 < below + kept.size()) return select(kept, below);
  return select(values, 0);
}

}  // namespace detail

/// The q-quantiles (0 ≤ q ≤ 1) of `values`, each interpolated linearly between the order
/// statistics at position q (n − 1) (Hyndman & Fan 1996, definition 7, the default of R and
/// NumPy): the minimum at q = 0, the median at 0.5, the maximum at 1; 0 for no values. In the
/// order of `qs`. O(n) per quantile on one copy of the values (selection, never a sort).
inline std::vector<double> quantiles(std::vector<double> values, const std::vector<double>& qs) {
  std::vector<double> out(qs.size(), 0.0);
  if (values.empty()) return out;
  for (std::size_t i = 0; i < qs.size(); ++i) {
    const double position = std::clamp(qs[i], 0.0, 1.0) * static_cast<double>(values.size() - 1);
    const auto below = static_cast<std::size_t>(std::floor(position));
    if (below + 1 >= values.size()) {
      out[i] = *std::max_element(values.begin(), values.end());
      continue;
    }
    const auto [low, high] = detail::order_statistics_at(values, below);
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
