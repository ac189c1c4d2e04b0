#include "analysis/identification/genetic_algorithm.h"

#include <algorithm>
#include <numeric>
#include <random>

#include "analysis/common/input_error.h"
#include "analysis/common/parallel_for.h"

namespace oscilab::analysis {
namespace {

void check(const GeneticOptions& o, int dimension) {
  if (dimension < 1) throw InputError("genetic algorithm: nothing to search (no free parameter)");
  if (o.population < 2) throw InputError("genetic algorithm: population must be at least 2");
  if (o.generations < 0) throw InputError("genetic algorithm: generations must be ≥ 0");
  if (o.elite < 0 || o.elite >= o.population) {
    throw InputError("genetic algorithm: elite count must lie in [0, population)");
  }
  if (!(o.mutation_rate >= 0.0 && o.mutation_rate <= 1.0)) {
    throw InputError("genetic algorithm: mutation rate must lie in [0, 1]");
  }
  if (!(o.crossover_fraction >= 0.0 && o.crossover_fraction <= 1.0)) {
    throw InputError("genetic algorithm: crossover fraction must lie in [0, 1]");
  }
  if (!(o.mutation_sigma > 0.0)) throw InputError("genetic algorithm: mutation σ must be positive");
}

}  // namespace

SearchResult genetic_algorithm(int dimension, const UnitCost& cost, const GeneticOptions& options,
                               const SearchProgressFn& progress, const CancelToken& cancel) {
  check(options, dimension);
  std::mt19937_64 rng(options.seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  const int n = options.population;

  std::vector<Eigen::VectorXd> members(n, Eigen::VectorXd(dimension));
  for (auto& m : members) {
    for (int j = 0; j < dimension; ++j) m(j) = uniform(rng);
  }
  std::vector<double> costs(n, 0.0);
  SearchResult result;
  const auto evaluate = [&](std::vector<Eigen::VectorXd>& points, std::vector<double>& out,
                            std::size_t first) {
    parallel_for(points.size() - first, options.threads,
                 [&](std::size_t i) { out[first + i] = cost(points[first + i]); });
    result.evaluations += static_cast<long>(points.size() - first);
  };
  evaluate(members, costs, 0);

  std::vector<int> order(n);
  const auto rank = [&] {
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return costs[a] < costs[b]; });
    result.best_unit = members[order[0]];
    result.best_cost = costs[order[0]];
    result.history.emplace_back(result.evaluations, result.best_cost);
    if (progress) progress({result.evaluations, result.best_cost, result.best_unit});
  };
  rank();

  const auto tournament = [&]() -> const Eigen::VectorXd& {
    const int a = static_cast<int>(uniform(rng) * n) % n;
    const int b = static_cast<int>(uniform(rng) * n) % n;
    return costs[a] <= costs[b] ? members[a] : members[b];
  };

  for (int g = 1; g <= options.generations; ++g) {
    if (cancel.cancelled()) {
      result.cancelled = true;
      break;
    }
    // σ shrinks linearly from mutation_sigma to a tenth of it over the run.
    const double progress_fraction =
        options.generations > 1 ? static_cast<double>(g - 1) / (options.generations - 1) : 0.0;
    const double sigma = options.mutation_sigma * (1.0 - 0.9 * progress_fraction);
    std::vector<Eigen::VectorXd> next;
    next.reserve(n);
    std::vector<double> next_costs(n, 0.0);
    for (int e = 0; e < options.elite; ++e) {
      next.push_back(members[order[e]]);
      next_costs[e] = costs[order[e]];
    }
    const int children = n - options.elite;
    const int crossed = static_cast<int>(std::lround(options.crossover_fraction * children));
    for (int c = 0; c < children; ++c) {
      Eigen::VectorXd child = tournament();
      if (c < crossed) {
        const Eigen::VectorXd& other = tournament();
        for (int j = 0; j < dimension; ++j) {
          if (uniform(rng) < 0.5) child(j) = other(j);
        }
      }
      for (int j = 0; j < dimension; ++j) {
        if (uniform(rng) < options.mutation_rate) {
          child(j) = std::clamp(child(j) + sigma * normal(rng), 0.0, 1.0);
        }
      }
      next.push_back(std::move(child));
    }
    evaluate(next, next_costs, static_cast<std::size_t>(options.elite));
    members = std::move(next);
    costs = std::move(next_costs);
    rank();
  }
  return result;
}

}  // namespace oscilab::analysis
