// A barrier for the threads of one OpenMP team that waits by spinning. The conjugate gradient's
// threads meet five times an iteration, a few microseconds apart: libgomp's barrier makes a
// futex system call at each one even when nobody sleeps, and std::barrier puts waiters to sleep
// (both measured slower: doc/performance.md). A wait longer than a few thousand spins (a thread
// descheduled) sleeps, and the last thread to arrive wakes sleepers only when there are any.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>

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
    const std::uint64_t ticket = arrivals_.fetch_add(1, std::memory_order_seq_cst);
    const std::uint64_t complete = (ticket / threads_ + 1) * threads_;
    if (ticket + 1 == complete) {
      // The last to arrive wakes those asleep, if any (seq_cst: a sleeper either counts itself
      // before this load or sees the arrival in its own check).
      if (sleepers_.load(std::memory_order_seq_cst) > 0) {
        std::lock_guard<std::mutex> lock(mutex_);
        wake_.notify_all();
      }
      return;
    }
    for (int spins = 0; spins < kSpinsBeforeSleep; ++spins) {
      if (arrivals_.load(std::memory_order_acquire) >= complete) return;
      pause();
    }
    // A long wait (another thread descheduled, the cores oversubscribed): sleep, as spinning on
    // would take the core from the thread waited for.
    std::unique_lock<std::mutex> lock(mutex_);
    sleepers_.fetch_add(1, std::memory_order_seq_cst);
    wake_.wait(lock, [&] { return arrivals_.load(std::memory_order_seq_cst) >= complete; });
    sleepers_.fetch_sub(1, std::memory_order_relaxed);
  }

 private:
  static constexpr int kSpinsBeforeSleep = 4096;  // far longer than threads of one step wait

  static void pause() {
#if defined(__x86_64__) || defined(__i386__)
    _mm_pause();
#endif
  }

  std::uint64_t threads_ = 1;
  alignas(64) std::atomic<std::uint64_t> arrivals_{0};
  alignas(64) std::atomic<int> sleepers_{0};
  std::mutex mutex_;
  std::condition_variable wake_;
};

}  // namespace deformable_sim::core
