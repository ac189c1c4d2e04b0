// The CMA-ES search on pagmo2, built as its own shared module (liboscilab_cmaes.so) and loaded
// by cmaes_search (cmaes_module_loader.cpp) on first use: libpagmo's static initialisers take
// about 8 ms and 36 MB at every process start, which every command that does not fit would pay.
#include "analysis/identification/cmaes_search.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <thread>

#include <pagmo/algorithms/cmaes.hpp>
#include <pagmo/population.hpp>
#include <pagmo/problem.hpp>

#include "analysis/common/input_error.h"
#include "analysis/common/parallel_for.h"

namespace oscilab::analysis {
namespace {

// pagmo user-defined problem: the unit cube and the cost.
struct UnitProblem {
  const UnitCost* cost = nullptr;
  int dimension = 0;
  pagmo::vector_double fitness(const pagmo::vector_double& x) const {
    const Eigen::VectorXd u = Eigen::Map<const Eigen::VectorXd>(x.data(), dimension);
    return {(*cost)(u)};
  }
  std::pair<pagmo::vector_double, pagmo::vector_double> get_bounds() const {
    return {pagmo::vector_double(dimension, 0.0), pagmo::vector_double(dimension, 1.0)};
  }
};

double spread(const pagmo::population& pop) {
  const auto& xs = pop.get_x();
  double widest = 0.0;
  for (std::size_t j = 0; j < xs.front().size(); ++j) {
    double lo = xs.front()[j], hi = lo;
    for (const auto& x : xs) {
      lo = std::min(lo, x[j]);
      hi = std::max(hi, x[j]);
    }
    widest = std::max(widest, hi - lo);
  }
  return widest;
}

}  // namespace

SearchResult run_cmaes(int dimension, const UnitCost& cost, const CmaesOptions& options,
                       const SearchProgressFn& progress, const CancelToken& cancel) {
  if (dimension < 1) throw InputError("CMA-ES: nothing to search (no free parameter)");
  if (options.max_evaluations < 10) throw InputError("CMA-ES: the budget must be ≥ 10 evaluations");
  if (!(options.sigma0 > 0.0 && options.sigma0 <= 1.0)) {
    throw InputError("CMA-ES: σ0 must lie in (0, 1]");
  }
  if (options.streams < 1 || options.streams > 1024) {
    throw InputError("CMA-ES: streams: " + std::to_string(options.streams) + " must be 1 to 1024");
  }
  const int hardware = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int streams = options.streams;
  const int threads = std::min(streams, options.threads > 0 ? options.threads : hardware);
  const int lambda0 = options.initial_population > 0
                          ? std::max(5, options.initial_population)
                          : std::max(8, 4 + static_cast<int>(3.0 * std::log(dimension)));

  std::vector<SearchResult> results(streams);
  std::mutex report_mutex;  // guards `global` and the progress calls
  SearchProgress global{0, std::numeric_limits<double>::infinity(), {}};
  std::atomic<long> spent_total{0};  // evaluations of all streams (each also counts its own)

  parallel_for(static_cast<std::size_t>(streams), threads, [&](std::size_t s) {
    SearchResult& r = results[s];
    r.best_cost = std::numeric_limits<double>::infinity();
    const long budget = options.max_evaluations / streams +
                        (static_cast<long>(s) < options.max_evaluations % streams ? 1 : 0);
    const pagmo::problem problem{UnitProblem{&cost, dimension}};
    int lambda = lambda0;
    for (int restart = 0; !cancel.cancelled(); ++restart, lambda *= 2) {
      if (r.evaluations + lambda > budget) break;
      const auto seed =
          static_cast<unsigned>((options.seed * 1000003u + s * 7919u + restart) & 0xffffffffu);
      pagmo::population pop(problem, static_cast<pagmo::population::size_type>(lambda), seed);
      r.evaluations += lambda;
      spent_total += lambda;
      // One generation per evolve() call with memory, so that cancellation, progress and the
      // budget are checked between generations.
      pagmo::algorithm algorithm{
          pagmo::cmaes(1u, -1, -1, -1, -1, options.sigma0, 1e-15, 1e-15, true, true, seed)};
      double run_best = std::numeric_limits<double>::infinity();
      int stalled = 0;
      for (;;) {
        const double champion = pop.champion_f()[0];
        if (champion < r.best_cost) {
          r.best_cost = champion;
          const auto& x = pop.champion_x();
          r.best_unit = Eigen::Map<const Eigen::VectorXd>(x.data(), dimension);
        }
        r.history.emplace_back(r.evaluations, r.best_cost);
        {
          const std::lock_guard lock(report_mutex);
          if (r.best_cost < global.best_cost) {
            global.best_cost = r.best_cost;
            global.best_unit = r.best_unit;
          }
          global.evaluations = spent_total.load();
          if (progress) progress(global);
        }
        if (champion < run_best * (1.0 - options.restart_ftol_rel) || !std::isfinite(run_best)) {
          run_best = champion;
          stalled = 0;
        } else if (++stalled >= options.stall_generations) {
          break;
        }
        const auto& f = pop.get_f();
        double worst = -std::numeric_limits<double>::infinity();
        for (const auto& v : f) worst = std::max(worst, v[0]);
        const bool flat = worst - champion <= 1e-12 * std::max(1.0, std::abs(champion));
        if (spread(pop) < options.restart_xtol || flat) break;
        if (cancel.cancelled() || r.evaluations + lambda > budget) break;
        pop = algorithm.evolve(pop);
        r.evaluations += lambda;
        spent_total += lambda;
      }
    }
    r.cancelled = cancel.cancelled();
  });

  // The best stream wins; histories are merged by evaluations spent so far in all streams.
  SearchResult out;
  out.best_cost = std::numeric_limits<double>::infinity();
  for (const SearchResult& r : results) {
    out.evaluations += r.evaluations;
    out.cancelled = out.cancelled || r.cancelled;
    if (r.best_cost < out.best_cost) {
      out.best_cost = r.best_cost;
      out.best_unit = r.best_unit;
    }
  }
  if (out.best_unit.size() == 0) out.best_unit = Eigen::VectorXd::Constant(dimension, 0.5);
  // Combined history: at each stream's step, the best over all streams up to that share of
  // their budgets (streams run at the same pace, so step i of each stream is simultaneous).
  std::size_t longest = 0;
  for (const SearchResult& r : results) longest = std::max(longest, r.history.size());
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < longest; ++i) {
    long spent = 0;
    for (const SearchResult& r : results) {
      if (r.history.empty()) continue;
      const std::size_t j = std::min(i, r.history.size() - 1);
      spent += r.history[j].first;
      best = std::min(best, r.history[j].second);
    }
    out.history.emplace_back(spent, best);
  }
  return out;
}

}  // namespace oscilab::analysis

// The module's one entry point (C linkage, so that dlsym finds it by this name). Exceptions cross
// it as C++ exceptions: the module and its loader are built by the same compiler in one build.
extern "C" __attribute__((visibility("default"))) void oscilab_cmaes_search_v1(
    int dimension, const oscilab::analysis::UnitCost* cost,
    const oscilab::analysis::CmaesOptions* options,
    const oscilab::analysis::SearchProgressFn* progress, const oscilab::CancelToken* cancel,
    oscilab::analysis::SearchResult* result) {
  *result = oscilab::analysis::run_cmaes(dimension, *cost, *options, *progress, *cancel);
}
