#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <functional>
#include <thread>
#include <vector>

namespace oscilab {

/// Runs body(i) for i in [0, count) on `threads` threads (0: all hardware threads), each taking
/// the next index from a shared counter, and returns when all are done. body must be safe to
/// call concurrently for different i and must not throw. The result of body(i) may not depend
/// on which thread runs it, so the outcome is the same for any thread count.
inline void parallel_for(std::size_t count, int threads,
                         const std::function<void(std::size_t)>& body) {
  const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t workers =
      std::min<std::size_t>(count, threads > 0 ? static_cast<std::size_t>(threads) : hardware);
  if (workers <= 1) {
    for (std::size_t i = 0; i < count; ++i) body(i);
    return;
  }
  std::atomic<std::size_t> next{0};
  const auto work = [&] {
    for (std::size_t i = next.fetch_add(1); i < count; i = next.fetch_add(1)) body(i);
  };
  std::vector<std::thread> pool;
  pool.reserve(workers - 1);
  for (std::size_t w = 1; w < workers; ++w) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
}

}  // namespace oscilab
