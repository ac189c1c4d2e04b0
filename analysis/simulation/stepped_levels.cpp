#include "analysis/simulation/stepped_levels.h"

#include <cmath>
#include <cstdio>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {
namespace {

constexpr double kWholeStepTolerance = 1e-9;  // of a step: absorbs (to − from)/step's rounding
constexpr double kMaxLevels = 10000;          // far beyond any test; bounds the allocation

}  // namespace

std::vector<double> stepped_levels(double from_n, double step_n, double to_n,
                                   const std::string& what) {
  if (!std::isfinite(from_n) || !std::isfinite(step_n) || !std::isfinite(to_n) || from_n < 0.0 ||
      !(step_n > 0.0) || to_n < from_n) {
    char values[96];
    std::snprintf(values, sizeof values, "from %g, step %g, to %g", from_n, step_n, to_n);
    throw InputError(what + ": " + values + ": needs 0 <= from <= to and step > 0");
  }
  const double steps = std::floor((to_n - from_n) / step_n + kWholeStepTolerance);
  if (steps + 1.0 > kMaxLevels) {
    throw InputError(what + ": more than 10000 levels; use a larger step");
  }
  std::vector<double> levels;
  levels.reserve(static_cast<std::size_t>(steps) + 1);
  for (int i = 0; i <= static_cast<int>(steps); ++i) levels.push_back(from_n + i * step_n);
  return levels;
}

}  // namespace oscilab::analysis
