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

/// A q-quantile of values seen one at a time, equal to quantile() of all of them, in memory for
/// the share beyond it only: the interpolation needs nothing but the values on its side. For
/// q ≥ 0.5 the largest values are kept, for q < 0.5 the smallest: at most `max_count` values
/// will be added, and the (1 − q) or q share of that bound (plus two) is kept in a heap, so the
/// p99 of a day-long 512 Hz record keeps 3.5 MB, not 350 MB.
class StreamedQuantile {
 public:
  StreamedQuantile(double q, std::size_t max_count)
      : q_(std::clamp(q, 0.0, 1.0)), upper_(q_ >= 0.5), keep_(kept_for(max_count)) {}

  void add(double value) {
    ++count_;
    const auto outranks = [this](double a, double b) { return upper_ ? a > b : a < b; };
    if (kept_.size() < keep_) {
      kept_.push_back(value);
      std::push_heap(kept_.begin(), kept_.end(), outranks);  // the least extreme on top
    } else if (outranks(value, kept_.front())) {
      std::pop_heap(kept_.begin(), kept_.end(), outranks);
      kept_.back() = value;
      std::push_heap(kept_.begin(), kept_.end(), outranks);
    }
  }
  std::size_t count() const { return count_; }

  /// quantile() of every value added (0 for none); at most max_count may have been added.
  double value() const {
    if (count_ == 0) return 0.0;
    std::vector<double> sorted = kept_;
    std::sort(sorted.begin(), sorted.end());
    const double position = q_ * static_cast<double>(count_ - 1);
    const auto below = static_cast<std::size_t>(std::floor(position));
    // The ascending ranks ⌊q (n − 1)⌋ and the one above, where the kept values sit among all.
    const std::size_t first_rank = upper_ ? count_ - sorted.size() : 0;
    if (below + 1 >= count_) return sorted.back();
    const double low = sorted[below - first_rank];
    const double high = sorted[below + 1 - first_rank];
    return low + (position - static_cast<double>(below)) * (high - low);
  }

 private:
  // The ranks needed, ⌊q (n − 1)⌋ and the next, lie within n − ⌊q (n − 1)⌋ of the top and
  // ⌊q (n − 1)⌋ + 2 of the bottom; both grow with n, so what max_count needs covers every
  // smaller count.
  std::size_t kept_for(std::size_t max_count) const {
    if (max_count == 0) return 1;
    const auto below =
        static_cast<std::size_t>(std::floor(q_ * static_cast<double>(max_count - 1)));
    return std::min(max_count, upper_ ? max_count - below + 1 : below + 2);
  }

  double q_;
  bool upper_;
  std::size_t keep_;
  std::size_t count_ = 0;
  std::vector<double> kept_;  // a heap of the most extreme values
};

}  // namespace oscilab
