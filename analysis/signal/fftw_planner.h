#pragma once

#include <cstddef>
#include <cstdlib>
#include <mutex>
#include <new>
#include <vector>

#include <fftw3.h>
#include <sys/mman.h>
#include <unistd.h>

namespace oscilab::analysis {

/// FFTW's planner (plan creation and destruction) is not thread-safe; its execute functions are.
/// Every place that makes or destroys a plan holds this one lock (FFTW manual, "Thread safety").
std::mutex& fftw_planner_mutex();

/// Allocates with fftw_malloc: arrays with the SIMD alignment the plans are made for
/// (RealFft). Every array given to such a plan must come from it (FftwVector). (FFTW_UNALIGNED
/// would accept any array, but FFTW then plans without its SIMD codelets' fast paths: measured
/// 19 ms r2c and 72 ms c2r to plan 276480 points, against 5.7 ms each aligned.)
///
/// A record's transforms use arrays of megabytes, and touching a fresh one costs a page fault
/// per 4 KiB, more than the transform itself. Arrays of 2 MiB and more are therefore aligned to
/// 2 MiB and advised as transparent huge pages (madvise MADV_HUGEPAGE): one fault per 2 MiB
/// where the kernel allows them ("madvise" or "always" in
/// /sys/kernel/mm/transparent_hugepage/enabled), plain pages elsewhere. Measured on `analyze` of
/// the two bundled records: 2 000 fewer page faults and 7 % less CPU (scripts/cli_speed.sh).
template <class T>
struct FftwAllocator {
  using value_type = T;
  static constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;
  FftwAllocator() = default;
  template <class U>
  explicit FftwAllocator(const FftwAllocator<U>& /*other*/) {}
  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (bytes >= kHugePageBytes) {
      void* p = nullptr;
      if (posix_memalign(&p, kHugePageBytes, bytes) != 0) throw std::bad_alloc();
      const auto page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
      madvise(p, bytes / page * page, MADV_HUGEPAGE);  // advice: without effect where refused
      return static_cast<T*>(p);
    }
    void* p = fftw_malloc(bytes);
    if (p == nullptr) throw std::bad_alloc();
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t n) {
    if (n * sizeof(T) >= kHugePageBytes) {
      std::free(p);  // NOLINT(cppcoreguidelines-no-malloc): posix_memalign's
    } else {
      fftw_free(p);
    }
  }
  friend bool operator==(const FftwAllocator& /*a*/, const FftwAllocator& /*b*/) { return true; }
};
template <class T>
using FftwVector = std::vector<T, FftwAllocator<T>>;

}  // namespace oscilab::analysis
