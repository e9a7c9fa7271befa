// A barrier for the threads of one OpenMP team that waits by spinning. The conjugate gradient's
// threads meet five times an iteration, a few microseconds apart: libgomp's barrier makes a
// futex system call at each one even when nobody sleeps (0.25 us against 0.04 us here for two
// threads, ~20 us of a 0.43 ms step), and std::barrier puts waiters to sleep (measured slower
// still). Waits longer than a few thousand spins (a thread descheduled) yield the core.
#pragma once

#include <atomic>
#include <cstdint>
#include <thread>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace deformable_sim::core {

class SpinBarrier {
 public:
  /// Sets the number of threads that meet. Not while any thread waits.
  void reset(int threads) {
    threads_ = threads;
    arrivals_.store(0, std::memory_order_relaxed);
  }

  /// Returns once all `threads` threads have called it; what each wrote before is then visible
  /// to all.
  void arriveAndWait() {
    // One counter of arrivals that never goes back (64 bits do not wrap): the k-th meeting is
    // complete when it reaches k * threads. One cache line, one atomic add a thread.
    const std::uint64_t ticket = arrivals_.fetch_add(1, std::memory_order_acq_rel);
    const std::uint64_t complete = (ticket / threads_ + 1) * threads_;
    for (int spins = 0; arrivals_.load(std::memory_order_acquire) < complete; ++spins) {
      if (spins < kSpinsBeforeYield) {
        pause();
      } else {
        std::this_thread::yield();
      }
    }
  }

 private:
  static constexpr int kSpinsBeforeYield = 4096;

  static void pause() {
#if defined(__x86_64__) || defined(__i386__)
    _mm_pause();
#endif
  }

  std::uint64_t threads_ = 1;
  alignas(64) std::atomic<std::uint64_t> arrivals_{0};
};

}  // namespace deformable_sim::core
