#pragma once
// The allocation guard of the tick-discipline tests: while armed, every call
// into the heap counts, whether it comes through operator new/delete (all
// forms) or straight through the C allocator (malloc, calloc, realloc,
// free, aligned_alloc, posix_memalign, memalign: Eigen and C code allocate
// there). alloc_guard.cpp replaces both in this test binary.
//
// In a sanitizer build the sanitizer owns malloc: there only operator
// new/delete are counted (kMallocCounted is false).
#include <cstddef>

namespace tnv::test {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define TNV_SANITIZER_OWNS_MALLOC 1
inline constexpr bool kMallocCounted = false;
#else
inline constexpr bool kMallocCounted = true;
#endif

void arm_allocation_guard() noexcept;
// Stops counting; returns the heap calls counted since arm_allocation_guard().
long disarm_allocation_guard() noexcept;

// Heap calls made by body().
template <typename Body>
long heap_calls_in(Body&& body) {
  arm_allocation_guard();
  body();
  return disarm_allocation_guard();
}

}  // namespace tnv::test
