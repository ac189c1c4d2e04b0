#pragma once

// Waiting, in the live chain's tests, for something another thread makes happen: a counter, a
// status field, an event. The deadline only guards against a hang (a loaded CI machine may take
// long, but never a minute); the tests assert what happened, never how long it took.

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <string>
#include <thread>

#include <gtest/gtest.h>

namespace oscilab::daq::testing {

constexpr std::chrono::seconds kHangGuard{60};

/// Polls `done` until it holds; a failure naming what never happened after `guard`.
template <typename Predicate>
::testing::AssertionResult eventually(Predicate done, const std::string& what,
                                      std::chrono::seconds guard = kHangGuard) {
  const auto deadline = std::chrono::steady_clock::now() + guard;
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) {
      return ::testing::AssertionFailure()
             << "never happened within " << guard.count() << " s: " << what;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return ::testing::AssertionSuccess();
}

/// Runs `action` (a call that must return, e.g. a stop()) on a thread of its own. When it has not
/// returned after `guard` it never will: the binary says what hung and aborts (a thread stuck in
/// the call cannot be joined, and a test that waits for it would hang instead of failing).
template <typename Action>
::testing::AssertionResult returns(Action action, const std::string& what,
                                   std::chrono::seconds guard = kHangGuard) {
  std::packaged_task<void()> task(std::move(action));
  std::future<void> done = task.get_future();
  std::thread thread(std::move(task));
  if (done.wait_for(guard) != std::future_status::ready) {
    std::fprintf(stderr, "never returned within %lld s: %s\n",
                 static_cast<long long>(guard.count()), what.c_str());
    std::abort();
  }
  thread.join();
  return ::testing::AssertionSuccess();
}

}  // namespace oscilab::daq::testing
