// The replaced global operator new and delete of a test executable that tracks its largest
// allocation (largest_allocation.h). malloc and free behind new and delete, on purpose; in a file
// of their own, no caller inlines both, so GCC's check that they match (-Wmismatched-new-delete)
// does not see them meet.
#include "tests/daq/recording/largest_allocation.h"

#include <cstdlib>

void* operator new(std::size_t size) { return oscilab::daq::testing::tracked_allocate(size); }
void* operator new[](std::size_t size) { return oscilab::daq::testing::tracked_allocate(size); }
void operator delete(void* pointer) noexcept { std::free(pointer); }
void operator delete[](void* pointer) noexcept { std::free(pointer); }
void operator delete(void* pointer, std::size_t /*size*/) noexcept { std::free(pointer); }
void operator delete[](void* pointer, std::size_t /*size*/) noexcept { std::free(pointer); }
