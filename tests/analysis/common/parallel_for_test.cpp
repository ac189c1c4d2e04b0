// parallel_for: every index exactly once, for any thread count, from concurrent callers and from
// a call nested in a body.
#include "analysis/common/parallel_for.h"

#include <atomic>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace oscilab {
namespace {

std::vector<int> run_counts(std::size_t count, int threads) {
  std::vector<std::atomic<int>> hits(count);
  parallel_for(count, threads, [&](std::size_t i) { hits[i].fetch_add(1); });
  std::vector<int> out;
  for (const auto& h : hits) out.push_back(h.load());
  return out;
}

TEST(ParallelFor, RunsEveryIndexExactlyOnceForAnyThreadCount) {
  for (const std::size_t count : {0u, 1u, 2u, 3u, 17u, 1000u}) {
    for (const int threads : {0, 1, 2, 3, 8}) {
      const std::vector<int> counts = run_counts(count, threads);
      for (std::size_t i = 0; i < count; ++i) {
        ASSERT_EQ(counts[i], 1) << "index " << i << " of " << count << ", threads " << threads;
      }
    }
  }
}

// Two threads calling at once, and a call nested in a body: every index of every call once.
TEST(ParallelFor, ConcurrentAndNestedCallsAreCorrect) {
  std::vector<int> a, b;
  std::thread other([&] { a = run_counts(20000, 2); });
  b = run_counts(20000, 2);
  other.join();
  for (std::size_t i = 0; i < 20000; ++i) {
    ASSERT_EQ(a[i], 1);
    ASSERT_EQ(b[i], 1);
  }
  std::vector<std::atomic<int>> hits(8 * 50);
  parallel_for(8, 2, [&](std::size_t outer) {
    parallel_for(50, 2, [&](std::size_t inner) { hits[outer * 50 + inner].fetch_add(1); });
  });
  for (const auto& h : hits) ASSERT_EQ(h.load(), 1);
}

}  // namespace
}  // namespace oscilab
