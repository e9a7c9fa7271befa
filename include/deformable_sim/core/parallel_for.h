// Loops split over threads with OpenMP, or run inline on one thread: entering an OpenMP region
// costs a futex system call even when the region runs on a single thread (~160 a step for CG,
// a quarter of a small body's step).
#pragma once

namespace deformable_sim::core {

/// body(i) for i in [begin, end), in static chunks over `threads` threads.
template <typename Function>
void parallelFor(int threads, int begin, int end, Function&& body) {
  if (threads > 1) {
#pragma omp parallel for num_threads(threads) schedule(static)
    for (int i = begin; i < end; ++i) body(i);
  } else {
    for (int i = begin; i < end; ++i) body(i);
  }
}

/// The sum of body(i) for i in [begin, end) (any order of summation over threads).
template <typename Function>
int parallelCount(int threads, int begin, int end, Function&& body) {
  int count = 0;
  if (threads > 1) {
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : count)
    for (int i = begin; i < end; ++i) count += body(i);
  } else {
    for (int i = begin; i < end; ++i) count += body(i);
  }
  return count;
}

}  // namespace deformable_sim::core
