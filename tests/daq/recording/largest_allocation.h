#pragma once

// The largest single request to the global operator new while a thread tracks its allocations:
// the fuzz tests bound what a file of a given size makes a reader allocate. A replaced global
// operator new must be defined once per executable: an executable that includes this header
// also compiles tests/daq/recording/largest_allocation.cpp, which defines the operators over
// tracked_allocate. Outside the tracked calls they only forward to malloc and free.

#include <cstddef>
#include <cstdlib>
#include <new>

namespace oscilab::daq::testing {

// Per thread: a test that reads on two threads tracks each on its own.
inline thread_local bool t_tracking_allocations = false;
inline thread_local std::size_t t_largest_allocation_bytes = 0;

/// Starts tracking this thread's allocations, from 0 bytes.
inline void start_tracking_allocations() {
  t_largest_allocation_bytes = 0;
  t_tracking_allocations = true;
}

/// Stops tracking; the largest single request since the start.
inline std::size_t stop_tracking_allocations() {
  t_tracking_allocations = false;
  return t_largest_allocation_bytes;
}

/// What the replaced operator new does: malloc, and note the size while tracking.
inline void* tracked_allocate(std::size_t size) {
  if (t_tracking_allocations && size > t_largest_allocation_bytes) {
    t_largest_allocation_bytes = size;
  }
  if (void* pointer = std::malloc(size == 0 ? 1 : size)) return pointer;
  throw std::bad_alloc();
}

}  // namespace oscilab::daq::testing
