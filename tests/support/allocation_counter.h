// SPDX-License-Identifier: MIT
#pragma once
// Counts calls of the global operator new, for tests that show a warm path
// does not touch the heap. Replaces the global operator new and delete, so
// include it from exactly one source file of a test binary.
#include <cstdlib>
#include <new>

namespace rwd::test {

/// Allocations made since the counting began, while it is on.
struct AllocationCounter {
  static inline bool counting = false;
  static inline long allocations = 0;

  /// Zeroes the count and starts counting.
  static void start() {
    allocations = 0;
    counting = true;
  }
  /// Stops counting; returns how many allocations there were.
  static long stop() {
    counting = false;
    return allocations;
  }
};

}  // namespace rwd::test

void* operator new(std::size_t size) {
  if (rwd::test::AllocationCounter::counting) ++rwd::test::AllocationCounter::allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
// The operator new above allocates with malloc, so free is its match; GCC
// 12 does not see that once it inlines these into a caller of the built-in
// operator new, and warns.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
