#pragma once
// Counts heap allocations by thread, for tests that show a path allocates nothing once warm.
// Include it in exactly one source file of a test binary: it replaces the global operator new
// and delete of that binary (new takes malloc's memory, delete gives it back with free).

#include <pthread.h>

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <thread>

namespace oscilab::testing {

/// While counting, every allocation of a thread other than the excluded ones is counted, and the
/// name of the first thread that allocated is kept (without allocating to keep it).
struct AllocationCounter {
  std::atomic<bool> counting{false};
  std::atomic<std::uint64_t> allocations{0};
  std::atomic<std::thread::id> excluded[2];
  char first_thread_name[32] = "";

  void start(std::thread::id excluded_a, std::thread::id excluded_b = {}) {
    excluded[0].store(excluded_a);
    excluded[1].store(excluded_b);
    allocations.store(0);
    first_thread_name[0] = '\0';
    counting.store(true);
  }
  std::uint64_t stop() {
    counting.store(false);
    return allocations.load();
  }
  void count() {
    if (!counting.load(std::memory_order_relaxed)) return;
    const std::thread::id self = std::this_thread::get_id();
    if (self == excluded[0].load() || self == excluded[1].load()) return;
    if (allocations.fetch_add(1) == 0) {
      pthread_getname_np(pthread_self(), first_thread_name, sizeof first_thread_name);
    }
  }
};

inline AllocationCounter allocation_counter;

}  // namespace oscilab::testing

// GCC sees malloc'd memory freed by this binary's own operator delete (which calls free) as a
// mismatch; here new and delete are a pair by construction.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

void* operator new(std::size_t size) {
  oscilab::testing::allocation_counter.count();
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
