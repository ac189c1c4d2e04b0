#pragma once

#include <functional>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace oscilab::analysis {

/// A cost over the unit cube [0, 1]^p (ModelForm::to_unit): what the search methods minimise.
/// Must be safe to call concurrently (populations are evaluated in parallel).
using UnitCost = std::function<double(const Eigen::VectorXd& unit)>;

/// Where a search stands, reported after every generation or polish step.
struct SearchProgress {
  long evaluations = 0;
  double best_cost = 0.0;
  Eigen::VectorXd best_unit;
};
using SearchProgressFn = std::function<void(const SearchProgress&)>;

/// The outcome of a search: the best point found, its cost, what it took, and the best cost
/// after each generation (evaluations, cost) for a convergence plot (Fig. 14).
struct SearchResult {
  Eigen::VectorXd best_unit;
  double best_cost = 0.0;
  long evaluations = 0;
  bool cancelled = false;
  std::vector<std::pair<long, double>> history;
};

}  // namespace oscilab::analysis
