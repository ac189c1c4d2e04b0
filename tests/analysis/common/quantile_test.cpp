// The one quantile helper (analysis/common/quantile.h) against its definition: linear
// interpolation between the order statistics of the sorted values (Hyndman & Fan's type 7).
#include "analysis/common/quantile.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace oscilab {
namespace {

TEST(Quantile, InterpolatesBetweenOrderStatistics) {
  const std::vector<double> v = {5.0, 1.0, 4.0, 2.0, 3.0};  // unsorted on purpose
  EXPECT_DOUBLE_EQ(quantile(v, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(quantile(v, 0.5), 3.0);
  EXPECT_DOUBLE_EQ(quantile(v, 1.0), 5.0);
  EXPECT_DOUBLE_EQ(quantile(v, 0.25), 2.0);
  EXPECT_DOUBLE_EQ(quantile(v, 0.1), 1.4);  // position 0.4 between 1 and 2
  EXPECT_DOUBLE_EQ(quantile({2.0, 1.0}, 0.5), 1.5);
  EXPECT_DOUBLE_EQ(quantile({7.0}, 0.3), 7.0);
  EXPECT_DOUBLE_EQ(quantile({}, 0.5), 0.0);
  EXPECT_DOUBLE_EQ(quantile(v, -1.0), 1.0);  // clamped to [0, 1]
  EXPECT_DOUBLE_EQ(quantile(v, 2.0), 5.0);
}

TEST(Quantile, EqualsTheSortedDefinitionOnRandomData) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal;
  for (int n : {2, 3, 10, 101, 1000}) {
    std::vector<double> v(static_cast<std::size_t>(n));
    for (double& x : v) x = normal(rng);
    std::vector<double> sorted = v;
    std::sort(sorted.begin(), sorted.end());
    for (double q : {0.0, 0.01, 0.025, 0.3, 0.5, 0.975, 0.99, 1.0}) {
      const double position = q * (n - 1);
      const auto k = static_cast<std::size_t>(position);
      const double expected = k + 1 < sorted.size()
                                  ? sorted[k] + (position - k) * (sorted[k + 1] - sorted[k])
                                  : sorted[k];
      EXPECT_NEAR(quantile(v, q), expected, 1e-15) << "n " << n << " q " << q;
    }
  }
}

// Several quantiles from one copy, asked in any order and with repeats, equal each asked
// alone; on data with many ties too.
TEST(Quantiles, EqualEachQuantileAskedAloneInAnyOrder) {
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> small(0, 6);
  std::normal_distribution<double> normal;
  const std::vector<double> qs = {0.99, 0.01, 0.5, 0.5, 1.0, 0.0, 0.975, 0.025, 0.3};
  for (bool ties : {false, true}) {
    for (int n : {1, 2, 3, 10, 101, 1000}) {
      std::vector<double> v(static_cast<std::size_t>(n));
      for (double& x : v) x = ties ? small(rng) : normal(rng);
      const std::vector<double> together = quantiles(v, qs);
      ASSERT_EQ(together.size(), qs.size());
      for (std::size_t i = 0; i < qs.size(); ++i) {
        EXPECT_EQ(together[i], quantile(v, qs[i])) << "n " << n << " q " << qs[i];
        // and the definition, independently of quantile():
        std::vector<double> sorted = v;
        std::sort(sorted.begin(), sorted.end());
        const double position = qs[i] * (n - 1);
        const auto k = static_cast<std::size_t>(position);
        const double expected = k + 1 < sorted.size()
                                    ? sorted[k] + (position - k) * (sorted[k + 1] - sorted[k])
                                    : sorted[k];
        EXPECT_NEAR(together[i], expected, 1e-15) << "n " << n << " q " << qs[i];
      }
    }
  }
  EXPECT_EQ(quantiles({}, {0.2, 0.8}), (std::vector<double>{0.0, 0.0}));
}

// Large arrays (where the ranks are bracketed from a sample first): random values, a sampled
// sine's |derivative| (periodic, as a record's speeds are; a strided sample would alias), many
// ties, and a constant; every quantile equals the sorted definition exactly.
TEST(Quantiles, LargeArraysEqualTheSortedDefinition) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal;
  std::uniform_int_distribution<int> small(0, 9);
  const std::vector<double> qs = {0.0, 0.01, 0.3, 0.5, 0.975, 0.99, 0.999, 1.0};
  for (int kind = 0; kind < 4; ++kind) {
    for (int n : {70000, 268800}) {
      std::vector<double> v(static_cast<std::size_t>(n));
      for (int i = 0; i < n; ++i) {
        const double x = kind == 0   ? normal(rng)
                         : kind == 1 ? std::abs(std::cos(2.0 * 3.141592653589793 * 9.0 * i / 512.0))
                         : kind == 2 ? small(rng)
                                     : 0.25;
        v[static_cast<std::size_t>(i)] = x;
      }
      std::vector<double> sorted = v;
      std::sort(sorted.begin(), sorted.end());
      const std::vector<double> got = quantiles(v, qs);
      for (std::size_t j = 0; j < qs.size(); ++j) {
        const double position = qs[j] * (n - 1);
        const auto k = static_cast<std::size_t>(position);
        const double expected = k + 1 < sorted.size()
                                    ? sorted[k] + (position - k) * (sorted[k + 1] - sorted[k])
                                    : sorted[k];
        EXPECT_EQ(got[j], expected) << "kind " << kind << " n " << n << " q " << qs[j];
      }
    }
  }
}

TEST(Median, IsTheMiddleValueOrTheMeanOfTheMiddleTwo) {
  EXPECT_EQ(median({}), 0.0);
  EXPECT_EQ(median({4.0}), 4.0);
  EXPECT_EQ(median({9.0, -1.0, 3.0}), 3.0);
  EXPECT_EQ(median({9.0, -1.0, 3.0, 5.0}), 4.0);
  EXPECT_EQ(median({2.0, 2.0, 7.0, 1.0, 2.0, 100.0}), 2.0);
}

// The streamed quantile keeps only the values beyond it and must give quantile() exactly, for
// every count up to the bound it was made for (a record's valid samples are fewer than its
// samples), on both sides of the median, on data with ties too.
TEST(StreamedQuantile, EqualsQuantileForEveryCountUpToItsBound) {
  std::mt19937_64 rng(29);
  std::normal_distribution<double> normal;
  for (const std::size_t bound : {1u, 2u, 7u, 100u, 1001u, 20000u}) {
    for (const double q : {0.0, 0.01, 0.3, 0.5, 0.9, 0.99, 1.0}) {
      for (const std::size_t n : {std::size_t{1}, bound / 2 + 1, bound}) {
        std::vector<double> v(n);
        for (double& x : v) x = std::round(normal(rng) * 50.0) / 10.0;  // ties
        StreamedQuantile streamed(q, bound);
        for (const double x : v) streamed.add(x);
        ASSERT_EQ(streamed.count(), n);
        EXPECT_EQ(streamed.value(), quantile(v, q))
            << "bound " << bound << " n " << n << " q " << q;
      }
    }
  }
  EXPECT_EQ(StreamedQuantile(0.99, 10).value(), 0.0);  // none added, as quantile({})
}

}  // namespace
}  // namespace oscilab
