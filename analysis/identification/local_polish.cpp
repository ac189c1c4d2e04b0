#include "analysis/identification/local_polish.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <nlopt.hpp>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {
namespace {

struct PolishState {
  const UnitCost* cost;
  const SearchProgressFn* progress;
  const CancelToken* cancel;
  SearchResult* result;
};

double objective(unsigned n, const double* x, double* /*gradient*/, void* data) {
  auto& state = *static_cast<PolishState*>(data);
  if (state.cancel->cancelled()) throw nlopt::forced_stop();
  const Eigen::VectorXd u = Eigen::Map<const Eigen::VectorXd>(x, n);
  const double value = (*state.cost)(u);
  SearchResult& r = *state.result;
  ++r.evaluations;
  if (value < r.best_cost) {
    r.best_cost = value;
    r.best_unit = u;
  }
  r.history.emplace_back(r.evaluations, r.best_cost);
  if (*state.progress) (*state.progress)({r.evaluations, r.best_cost, r.best_unit});
  return value;
}

}  // namespace

SearchResult local_polish(const Eigen::VectorXd& start_unit, const UnitCost& cost,
                          const PolishOptions& options, const SearchProgressFn& progress,
                          const CancelToken& cancel) {
  const int n = static_cast<int>(start_unit.size());
  if (n < 1) throw InputError("local polish: nothing to search (no free parameter)");
  SearchResult result;
  result.best_unit = start_unit;
  result.best_cost = std::numeric_limits<double>::infinity();
  if (options.max_evaluations <= 0) return result;
  // Powell's BOBYQA needs two or more parameters for its quadratic model; a single parameter
  // is refined by NLopt's Subplex (Nelder–Mead on subspaces) instead.
  nlopt::opt opt(n >= 2 ? nlopt::LN_BOBYQA : nlopt::LN_SBPLX, static_cast<unsigned>(n));
  opt.set_lower_bounds(std::vector<double>(n, 0.0));
  opt.set_upper_bounds(std::vector<double>(n, 1.0));
  PolishState state{&cost, &progress, &cancel, &result};
  opt.set_min_objective(objective, &state);
  opt.set_maxeval(static_cast<int>(options.max_evaluations));
  opt.set_xtol_rel(options.xtol_rel);
  opt.set_ftol_rel(options.ftol_rel);
  std::vector<double> step(n), x(n);
  for (int i = 0; i < n; ++i) {
    x[i] = std::clamp(start_unit(i), 0.0, 1.0);
    // The first trust region must fit inside the cube on the side it points to.
    step[i] = std::min(options.initial_step, std::max(x[i], 1.0 - x[i]));
  }
  opt.set_initial_step(step);
  double value = 0.0;
  try {
    opt.optimize(x, value);
  } catch (const nlopt::forced_stop&) {
    result.cancelled = true;
  } catch (const std::runtime_error&) {
    // NLopt's generic failure (e.g. a round-off limited stop): the best point so far stands.
  }
  return result;
}

}  // namespace oscilab::analysis
