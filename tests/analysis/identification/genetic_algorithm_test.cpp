#include "analysis/identification/genetic_algorithm.h"

#include <atomic>
#include <cmath>
#include <functional>
#include <limits>
#include <mutex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"
#include "tests/analysis/identification/search_test_costs.h"

namespace oscilab::analysis {
namespace {

using testing::input_error_of;
using testing::rosenbrock_unit;

// A shifted sphere with its minimum 0 at `centre`, inside the unit cube.
UnitCost sphere(const Eigen::VectorXd& centre) {
  return [centre](const Eigen::VectorXd& u) { return (u - centre).squaredNorm(); };
}

GeneticOptions paper_options(std::uint64_t seed) {
  GeneticOptions o;  // the paper's settings: population 100, 20 generations, 20 % mutation
  o.seed = seed;
  o.threads = 1;  // the result does not depend on it (checked below), and threads cost start-up
  return o;
}

// The paper's budget (2000 evaluations) on a 3-D sphere: every one of ten seeds ends within 0.01,
// the last generation's mutation σ, of the minimum in each coordinate (the elite keep the best,
// and the shrinking steps refine around it). Measured over seeds 1–50: at most 0.0036.
TEST(GeneticAlgorithm, PaperBudgetFindsTheMinimumOfAShiftedSphere) {
  Eigen::VectorXd centre(3);
  centre << 0.3, 0.71, 0.55;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const SearchResult r = genetic_algorithm(3, sphere(centre), paper_options(seed));
    SCOPED_TRACE("seed " + std::to_string(seed));
    ASSERT_EQ(r.best_unit.size(), 3);
    EXPECT_LT((r.best_unit - centre).cwiseAbs().maxCoeff(), 0.01) << r.best_unit.transpose();
    // best_cost is the cost of best_unit, not an estimate.
    EXPECT_EQ(r.best_cost, sphere(centre)(r.best_unit));
    EXPECT_FALSE(r.cancelled);
  }
}

// Rosenbrock's curved valley is hard for a GA: with a larger budget (200 × 60) it reaches the
// valley floor near the minimum (measured over seeds 1–10: f ≤ 4e-3). Near the unique minimum
// u = (0.75, 0.75), f < 1e-2 on the valley floor y = x² means |1 − x| < 0.1, so u₀ within 0.025
// and u₁ (y ≈ 1 + 2(x − 1)) within 0.05 of 0.75; 0.03 allows for the floor's width.
TEST(GeneticAlgorithm, LargerBudgetReachesTheRosenbrockMinimum) {
  GeneticOptions o = paper_options(3);
  o.population = 200;
  o.generations = 60;
  o.elite = 10;
  const SearchResult r = genetic_algorithm(2, rosenbrock_unit, o);
  EXPECT_LT(r.best_cost, 1e-2);
  EXPECT_NEAR(r.best_unit(0), 0.75, 0.03);
  EXPECT_NEAR(r.best_unit(1), 0.75, 0.05);
}

// The documented budget: population + generations × (population − elite) calls of the cost,
// every point inside the unit cube, and one history entry per generation (and generation 0) whose
// best cost never rises (the elite survive) and whose evaluation counts are the budget so far.
TEST(GeneticAlgorithm, SpendsExactlyTheDocumentedBudgetInsideTheCube) {
  GeneticOptions o = paper_options(5);
  o.population = 30;
  o.generations = 12;
  o.elite = 3;
  o.threads = 2;  // the evaluations of a generation run concurrently: all are counted
  std::atomic<long> calls{0};
  std::atomic<bool> outside{false};
  Eigen::VectorXd centre = Eigen::VectorXd::Constant(4, 0.98);  // near a face: clipping matters
  const UnitCost cost = [&](const Eigen::VectorXd& u) {
    ++calls;
    if ((u.array() < 0.0).any() || (u.array() > 1.0).any()) outside = true;
    return (u - centre).squaredNorm();
  };
  const SearchResult r = genetic_algorithm(4, cost, o);
  const long budget = 30 + 12 * (30 - 3);
  EXPECT_EQ(r.evaluations, budget);
  EXPECT_EQ(calls.load(), budget);
  EXPECT_FALSE(outside.load());
  ASSERT_EQ(r.history.size(), 13u);
  for (std::size_t g = 0; g < r.history.size(); ++g) {
    EXPECT_EQ(r.history[g].first, 30 + static_cast<long>(g) * 27);
    if (g > 0) {
      EXPECT_LE(r.history[g].second, r.history[g - 1].second);
    }
  }
  EXPECT_EQ(r.history.back().second, r.best_cost);
}

// The same seed gives the same result, bit for bit, on one thread or two (all draws happen on the
// calling thread); another seed gives another path.
TEST(GeneticAlgorithm, SameSeedGivesTheSameResultForAnyThreadCount) {
  Eigen::VectorXd centre(5);
  centre << 0.1, 0.2, 0.3, 0.4, 0.5;
  GeneticOptions o = paper_options(11);
  o.population = 40;
  o.generations = 10;
  o.threads = 1;
  const SearchResult one = genetic_algorithm(5, sphere(centre), o);
  o.threads = 2;
  const SearchResult two = genetic_algorithm(5, sphere(centre), o);
  EXPECT_EQ(one.best_cost, two.best_cost);
  EXPECT_EQ(one.best_unit, two.best_unit);
  EXPECT_EQ(one.history, two.history);
  o.seed = 12;
  const SearchResult other = genetic_algorithm(5, sphere(centre), o);
  EXPECT_NE(other.best_unit, one.best_unit);
}

// Without crossover and mutation every child is a copy of a parent: no new point is ever made, so
// the best after any number of generations is the best of generation 0.
TEST(GeneticAlgorithm, WithoutVariationTheBestOfGenerationZeroStays) {
  GeneticOptions o = paper_options(21);
  o.population = 25;
  o.generations = 8;
  o.mutation_rate = 0.0;
  o.crossover_fraction = 0.0;
  std::mutex mutex;
  std::vector<Eigen::VectorXd> points;
  const Eigen::VectorXd centre = Eigen::VectorXd::Constant(2, 0.5);
  const UnitCost cost = [&](const Eigen::VectorXd& u) {
    const std::lock_guard lock(mutex);
    points.push_back(u);
    return (u - centre).squaredNorm();
  };
  const SearchResult r = genetic_algorithm(2, cost, o);
  ASSERT_EQ(points.size(), 25u + 8u * (25u - 5u));
  double best0 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < 25; ++i) best0 = std::min(best0, (points[i] - centre).squaredNorm());
  EXPECT_EQ(r.best_cost, best0);
  for (const auto& [evaluations, best] : r.history) EXPECT_EQ(best, best0) << evaluations;
  // Every later point is one of generation 0's (threads make the order of `points` vary within a
  // generation, so compare as a set).
  for (std::size_t k = 25; k < points.size(); ++k) {
    bool found = false;
    for (std::size_t i = 0; i < 25 && !found; ++i) found = points[k] == points[i];
    EXPECT_TRUE(found) << "point " << k << " is new: " << points[k].transpose();
  }
}

// The mutation σ shrinks linearly from mutation_sigma (generation 1) to a tenth of it (the last).
// With one child per generation (population 2, elite 1), no crossover and every gene mutated,
// the child is its parent plus σ_g·N(0, 1) in each of 4000 genes; the parent is whichever of the
// two previous members is nearer (the other differs by an earlier mutation, ~σ√4000 away). Genes
// whose parent lies in [0.2, 0.8] are never clipped (≥ 10 σ from a face), and their RMS step
// estimates σ_g with a standard error of 1/√(2·2400) ≈ 1.4 %: ±6 % is 4 standard errors.
TEST(GeneticAlgorithm, MutationSigmaShrinksLinearlyToATenth) {
  const int dimension = 4000;
  GeneticOptions o = paper_options(31);
  o.population = 2;
  o.elite = 1;
  o.generations = 10;
  o.crossover_fraction = 0.0;
  o.mutation_rate = 1.0;
  o.mutation_sigma = 0.02;
  o.threads = 1;
  std::vector<Eigen::VectorXd> points;  // in evaluation order (one thread)
  const UnitCost cost = [&](const Eigen::VectorXd& u) {
    points.push_back(u);
    return u.sum();
  };
  genetic_algorithm(dimension, cost, o);
  ASSERT_EQ(points.size(), 2u + 10u);
  // Members of generation g − 1: the elite (the lower sum) and the other.
  Eigen::VectorXd a = points[0], b = points[1];
  for (int g = 1; g <= 10; ++g) {
    const Eigen::VectorXd& child = points[1 + static_cast<std::size_t>(g)];
    const Eigen::VectorXd& parent = (child - a).norm() < (child - b).norm() ? a : b;
    double sum2 = 0.0;
    int count = 0;
    for (int j = 0; j < dimension; ++j) {
      if (parent(j) < 0.2 || parent(j) > 0.8) continue;
      sum2 += (child(j) - parent(j)) * (child(j) - parent(j));
      ++count;
    }
    const double expected = 0.02 * (1.0 - 0.9 * (g - 1) / 9.0);
    EXPECT_NEAR(std::sqrt(sum2 / count) / expected, 1.0, 0.06) << "generation " << g;
    // Next generation: the elite (lower cost) and the child.
    const Eigen::VectorXd elite = a.sum() <= b.sum() ? a : b;
    a = elite;
    b = child;
  }
}

// Cancellation is polled before each generation: cancelled from the progress report after
// generation 2, the run stops there with that generation's best and its exact evaluation count.
TEST(GeneticAlgorithm, CancellationStopsBeforeTheNextGeneration) {
  GeneticOptions o = paper_options(41);
  o.population = 20;
  o.elite = 2;
  o.generations = 50;
  const CancelToken cancel;
  int reports = 0;
  const SearchProgressFn progress = [&](const SearchProgress& p) {
    ++reports;
    EXPECT_EQ(p.evaluations, 20 + (reports - 1) * 18);
    if (reports == 3) cancel.cancel();  // after generation 0, 1, 2
  };
  const SearchResult r =
      genetic_algorithm(3, sphere(Eigen::VectorXd::Constant(3, 0.4)), o, progress, cancel);
  EXPECT_TRUE(r.cancelled);
  EXPECT_EQ(reports, 3);
  EXPECT_EQ(r.evaluations, 20 + 2 * 18);
  ASSERT_EQ(r.history.size(), 3u);
  EXPECT_EQ(r.history.back().second, r.best_cost);

  // A token cancelled up front: generation 0 only.
  const SearchResult early =
      genetic_algorithm(3, sphere(Eigen::VectorXd::Constant(3, 0.4)), o, {}, cancel);
  EXPECT_TRUE(early.cancelled);
  EXPECT_EQ(early.evaluations, 20);
}

TEST(GeneticAlgorithm, ZeroGenerationsIsTheBestOfTheInitialSample) {
  GeneticOptions o = paper_options(51);
  o.generations = 0;
  const SearchResult r = genetic_algorithm(2, sphere(Eigen::VectorXd::Constant(2, 0.5)), o);
  EXPECT_EQ(r.evaluations, 100);
  EXPECT_EQ(r.history.size(), 1u);
  EXPECT_FALSE(r.cancelled);
}

TEST(GeneticAlgorithm, ThrowsInputErrorNamingTheBadSetting) {
  const UnitCost cost = sphere(Eigen::VectorXd::Constant(2, 0.5));
  const auto error_with = [&](int dimension, const std::function<void(GeneticOptions&)>& change) {
    GeneticOptions o = paper_options(1);
    change(o);
    return input_error_of([&] { genetic_algorithm(dimension, cost, o); });
  };
  EXPECT_NE(error_with(0, [](GeneticOptions&) {}).find("no free parameter"), std::string::npos);
  EXPECT_NE(error_with(2, [](GeneticOptions& o) { o.population = 1; }).find("population"),
            std::string::npos);
  EXPECT_NE(error_with(2, [](GeneticOptions& o) { o.generations = -1; }).find("generations"),
            std::string::npos);
  EXPECT_NE(error_with(2, [](GeneticOptions& o) { o.elite = 100; }).find("elite"),
            std::string::npos);
  EXPECT_NE(error_with(2, [](GeneticOptions& o) { o.elite = -1; }).find("elite"),
            std::string::npos);
  EXPECT_NE(error_with(2, [](GeneticOptions& o) { o.mutation_rate = 1.5; }).find("mutation rate"),
            std::string::npos);
  EXPECT_NE(
      error_with(
          2, [](GeneticOptions& o) { o.mutation_rate = std::numeric_limits<double>::quiet_NaN(); })
          .find("mutation rate"),
      std::string::npos);
  EXPECT_NE(error_with(2, [](GeneticOptions& o) { o.crossover_fraction = -0.1; }).find("crossover"),
            std::string::npos);
  EXPECT_NE(error_with(2, [](GeneticOptions& o) { o.mutation_sigma = 0.0; }).find("mutation σ"),
            std::string::npos);
  // The edges of the ranges are valid.
  EXPECT_EQ(error_with(2,
                       [](GeneticOptions& o) {
                         o.population = 2;
                         o.elite = 1;
                         o.generations = 1;
                         o.mutation_rate = 1.0;
                         o.crossover_fraction = 0.0;
                       }),
            "");
}

}  // namespace
}  // namespace oscilab::analysis
