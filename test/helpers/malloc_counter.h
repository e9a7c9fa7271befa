// Every heap allocation of a test binary goes through malloc (operator new and Eigen both call
// it): this interposes it and counts the calls, forwarding to glibc's own implementation.
// Include it in one file per test binary only: it defines malloc, calloc and realloc.
#pragma once

#include <atomic>
#include <cstddef>

extern "C" {
void* __libc_malloc(size_t size);
void* __libc_calloc(size_t count, size_t size);
void* __libc_realloc(void* p, size_t size);
}

namespace deformable_sim::test {
/// Heap allocations since the binary started.
inline std::atomic<long> g_allocations{0};
}  // namespace deformable_sim::test

extern "C" {
void* malloc(size_t size) {
  ++deformable_sim::test::g_allocations;
  return __libc_malloc(size);
}
void* calloc(size_t count, size_t size) {
  ++deformable_sim::test::g_allocations;
  return __libc_calloc(count, size);
}
void* realloc(void* p, size_t size) {
  ++deformable_sim::test::g_allocations;
  return __libc_realloc(p, size);
}
}
