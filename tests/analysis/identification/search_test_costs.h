#pragma once
// Test costs and helpers shared by the unit-cube search tests (GA, CMA-ES).
#include <Eigen/Core>

#include "tests/input_error_of.h"

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

using oscilab::testing::input_error_of;

}  // namespace oscilab::analysis::testing
