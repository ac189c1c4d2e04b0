#pragma once
// Test costs and helpers shared by the unit-cube search tests (GA, CMA-ES).
#include <functional>
#include <string>

#include <Eigen/Core>

#include "analysis/common/input_error.h"

namespace oscilab::analysis::testing {

// Rosenbrock on x = 4u − 2 ∈ [−2, 2]^p: minimum 0 at x = (1, …, 1), u = (0.75, …, 0.75).
inline double rosenbrock_unit(const Eigen::VectorXd& u) {
  double f = 0.0;
  for (Eigen::Index i = 0; i + 1 < u.size(); ++i) {
    const double x = 4.0 * u(i) - 2.0, y = 4.0 * u(i + 1) - 2.0;
    f += 100.0 * (y - x * x) * (y - x * x) + (1.0 - x) * (1.0 - x);
  }
  return f;
}

// The message of the InputError that `action` throws, or "" when it throws none.
inline std::string input_error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

}  // namespace oscilab::analysis::testing
