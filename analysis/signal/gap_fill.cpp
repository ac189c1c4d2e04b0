#include "analysis/signal/gap_fill.h"

#include <cmath>

namespace oscilab::analysis {

long fill_non_finite(Eigen::VectorXd& x) {
  const Eigen::Index n = x.size();
  long filled = 0;
  Eigen::Index i = 0;
  while (i < n) {
    if (std::isfinite(x[i])) {
      ++i;
      continue;
    }
    Eigen::Index end = i;  // first finite sample after the run, or n
    while (end < n && !std::isfinite(x[end])) ++end;
    const bool has_left = i > 0, has_right = end < n;
    const double left = has_left ? x[i - 1] : (has_right ? x[end] : 0.0);
    const double right = has_right ? x[end] : left;
    const double span = static_cast<double>(end - i + 1);
    for (Eigen::Index k = i; k < end; ++k) {
      const double s = static_cast<double>(k - i + 1) / span;
      x[k] = left + s * (right - left);
    }
    filled += static_cast<long>(end - i);
    i = end;
  }
  return filled;
}

}  // namespace oscilab::analysis
