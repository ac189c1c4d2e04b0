// The CMA-ES search runs in liboscilab_cmaes.so, loaded from ../lib/oscilab beside this test's
// directory (the build puts it there: target oscilab_cmaes).
#include "analysis/identification/cmaes_search.h"

#include <atomic>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"
#include "tests/analysis/identification/search_test_costs.h"

namespace oscilab::analysis {
namespace {

using testing::input_error_of;
using testing::rosenbrock_unit;

// A shifted, anisotropic quadratic with its minimum 0 at u = c_i = 0.2 + 0.6 i/(p − 1) and axis
// weights 1 … 100 (condition number 100).
double quadratic_unit(const Eigen::VectorXd& u) {
  const Eigen::Index p = u.size();
  double f = 0.0;
  for (Eigen::Index i = 0; i < p; ++i) {
    const double c = p > 1 ? 0.2 + 0.6 * static_cast<double>(i) / static_cast<double>(p - 1) : 0.4;
    const double weight = p > 1 ? std::pow(100.0, static_cast<double>(i) / (p - 1)) : 1.0;
    f += weight * (u(i) - c) * (u(i) - c);
  }
  return f;
}

Eigen::VectorXd quadratic_minimum(int p) {
  Eigen::VectorXd c(p);
  for (int i = 0; i < p; ++i) c(i) = p > 1 ? 0.2 + 0.6 * i / (p - 1.0) : 0.4;
  return c;
}

CmaesOptions options_with(long budget, std::uint64_t seed = 1, int streams = 2) {
  CmaesOptions o;
  o.max_evaluations = budget;
  o.streams = streams;
  o.seed = seed;
  return o;
}

// A quadratic's minimum is found to the accuracy CMA-ES reaches before its restart tests stop a
// run: a run ends when its population's spread falls below restart_xtol = 1e-6 (or its costs are
// flat), where the best cost is ≲ weight·spread² ≤ 1e-10 (measured over seeds 1–3: ≤ 3e-13).
// Every weight is ≥ 1, so f < 1e-10 puts each coordinate within √f = 1e-5 of the minimum.
TEST(CmaesSearch, FindsTheMinimumOfAQuadraticIn2To5Dimensions) {
  for (int p = 2; p <= 5; ++p) {
    SCOPED_TRACE("dimension " + std::to_string(p));
    const SearchResult r = cmaes_search(p, quadratic_unit, options_with(3000));
    ASSERT_EQ(r.best_unit.size(), p);
    EXPECT_LT(r.best_cost, 1e-10);
    EXPECT_LT((r.best_unit - quadratic_minimum(p)).cwiseAbs().maxCoeff(), 1e-5)
        << r.best_unit.transpose();
    EXPECT_EQ(r.best_cost, quadratic_unit(r.best_unit));
    EXPECT_FALSE(r.cancelled);
  }
}

// Rosenbrock's valley: near the minimum f ≈ ½ δxᵀHδx with H's eigenvalues from 0.40 (2-D) or
// 0.50 (5-D) to ~1000-1650, so f < 1e-10 puts x within √(2f/0.4) = 2.2e-5 of (1, …, 1) and u
// (x = 4u − 2) within 5.6e-6 of 0.75: 1e-5. Measured over seeds 1–5 at these budgets: f ≤ 5e-13.
TEST(CmaesSearch, FindsTheRosenbrockMinimumIn2And5Dimensions) {
  for (int p : {2, 5}) {
    SCOPED_TRACE("dimension " + std::to_string(p));
    const SearchResult r = cmaes_search(p, rosenbrock_unit, options_with(p == 2 ? 3000 : 12000));
    EXPECT_LT(r.best_cost, 1e-10);
    EXPECT_LT((r.best_unit.array() - 0.75).abs().maxCoeff(), 1e-5) << r.best_unit.transpose();
  }
}

// The budget is a hard limit, counted by the cost's own calls: the result's count is the number of
// calls, and it never exceeds max_evaluations (a restart whose first population would not fit is
// not started). The histories' evaluation counts rise.
TEST(CmaesSearch, NeverExceedsTheEvaluationBudget) {
  for (long budget : {10L, 57L, 400L, 2500L}) {
    for (int streams : {1, 3}) {
      SCOPED_TRACE("budget " + std::to_string(budget) + ", streams " + std::to_string(streams));
      std::atomic<long> calls{0};
      const UnitCost cost = [&](const Eigen::VectorXd& u) {
        ++calls;
        return rosenbrock_unit(u);
      };
      const SearchResult r = cmaes_search(3, cost, options_with(budget, 7, streams));
      EXPECT_EQ(r.evaluations, calls.load());
      EXPECT_LE(r.evaluations, budget);
      for (std::size_t i = 1; i < r.history.size(); ++i) {
        EXPECT_GE(r.history[i].first, r.history[i - 1].first);
        EXPECT_LE(r.history[i].second, r.history[i - 1].second);
      }
    }
  }
}

// Each restart sequence is seeded from the seed and its index: the same seed and stream count
// give the same result bit for bit, however the threads interleave; another seed another one.
TEST(CmaesSearch, SameSeedAndStreamCountReproduceTheResult) {
  const auto run = [](std::uint64_t seed) {
    return cmaes_search(4, rosenbrock_unit, options_with(1200, seed, 3));
  };
  const SearchResult a = run(5), b = run(5), c = run(6);
  EXPECT_EQ(a.best_unit, b.best_unit);
  EXPECT_EQ(a.best_cost, b.best_cost);
  EXPECT_EQ(a.evaluations, b.evaluations);
  EXPECT_EQ(a.history, b.history);
  EXPECT_NE(a.best_unit, c.best_unit);
}

// The threads run the streams, they do not make them: one thread and three give the same search
// bit for bit (what a diagnosis on a laptop, a cluster node or at --threads 1 relies on).
TEST(CmaesSearch, ThreadsDoNotChangeTheResult) {
  const auto run = [](int threads) {
    CmaesOptions o = options_with(1200, 5, 3);
    o.threads = threads;
    return cmaes_search(4, rosenbrock_unit, o);
  };
  const SearchResult one = run(1), three = run(3);
  EXPECT_EQ(one.best_unit, three.best_unit);
  EXPECT_EQ(one.best_cost, three.best_cost);
  EXPECT_EQ(one.evaluations, three.evaluations);
}

// Cancellation is polled between generations: cancelled from a progress report, every stream
// stops within a generation, so far fewer than the budget are spent; the best so far is kept.
TEST(CmaesSearch, CancellationStopsTheSearchWithItsBestSoFar) {
  const CancelToken cancel;
  std::atomic<int> reports{0};
  const SearchProgressFn progress = [&](const SearchProgress& p) {
    EXPECT_TRUE(std::isfinite(p.best_cost));
    if (++reports == 5) cancel.cancel();
  };
  const SearchResult r =
      cmaes_search(3, rosenbrock_unit, options_with(100000, 1, 2), progress, cancel);
  EXPECT_TRUE(r.cancelled);
  // Five reports of two streams at λ = 8: a few dozen evaluations, plus at most one generation
  // per stream after the cancel.
  EXPECT_LT(r.evaluations, 200);
  EXPECT_TRUE(std::isfinite(r.best_cost));
  EXPECT_EQ(r.best_cost, rosenbrock_unit(r.best_unit));

  // Cancelled up front: nothing is evaluated; the best is the cube's centre, unevaluated.
  std::atomic<long> calls{0};
  const SearchResult none = cmaes_search(
      3,
      [&](const Eigen::VectorXd& u) {
        ++calls;
        return rosenbrock_unit(u);
      },
      options_with(1000), {}, cancel);
  EXPECT_TRUE(none.cancelled);
  EXPECT_EQ(none.evaluations, 0);
  EXPECT_EQ(calls.load(), 0);
  EXPECT_EQ(none.best_unit, Eigen::VectorXd::Constant(3, 0.5));
}

TEST(CmaesSearch, ThrowsInputErrorForInvalidSettings) {
  const auto error_with = [](int dimension, const std::function<void(CmaesOptions&)>& change) {
    CmaesOptions o = options_with(100);
    change(o);
    return input_error_of([&] { cmaes_search(dimension, quadratic_unit, o); });
  };
  EXPECT_NE(error_with(0, [](CmaesOptions&) {}).find("no free parameter"), std::string::npos);
  EXPECT_NE(error_with(2, [](CmaesOptions& o) { o.max_evaluations = 9; }).find("budget"),
            std::string::npos);
  for (double sigma0 : {0.0, -0.1, 1.0001, std::numeric_limits<double>::quiet_NaN()}) {
    EXPECT_NE(error_with(2, [&](CmaesOptions& o) { o.sigma0 = sigma0; }).find("σ0"),
              std::string::npos)
        << sigma0;
  }
  for (int streams : {0, -1, 1025}) {
    EXPECT_NE(error_with(2, [&](CmaesOptions& o) { o.streams = streams; }).find("streams"),
              std::string::npos)
        << streams;
  }
  // The edges: a budget of 10, σ0 = 1.
  EXPECT_EQ(error_with(1,
                       [](CmaesOptions& o) {
                         o.max_evaluations = 10;
                         o.sigma0 = 1.0;
                       }),
            "");
}

}  // namespace
}  // namespace oscilab::analysis
