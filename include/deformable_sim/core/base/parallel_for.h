// Loops split over threads with OpenMP, or run inline on one thread: entering an OpenMP region
// costs a futex system call even when the region runs on a single thread, and CG enters many a
// step: on a small body that is a good part of the step.
#pragma once

#include <algorithm>
#include <vector>

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

/// body(i) for i in [begin, end), each index taken by the next free thread: for a few items of
/// uneven cost (bodies of different sizes). body(i) must give the same result on any thread.
template <typename Function>
void parallelForEach(int threads, int begin, int end, Function&& body) {
  if (threads > 1) {
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
    for (int i = begin; i < end; ++i) body(i);
  } else {
    for (int i = begin; i < end; ++i) body(i);
  }
}

/// The sum of body(i) for i in [begin, end) (a Value with +=), taken in fixed chunks of `chunk`
/// indices whose sums are added in chunk order: the same bits on any thread count. `partials`
/// holds the chunk sums (resized on the first call only).
template <typename Value, typename Function>
Value parallelChunkedSum(int threads, int begin, int end, int chunk, std::vector<Value>& partials,
                         Function&& body) {
  const int num_chunks = (end - begin + chunk - 1) / chunk;
  if (static_cast<int>(partials.size()) < num_chunks) partials.resize(num_chunks);
  parallelFor(threads, 0, num_chunks, [&](int c) {
    Value sum{};
    const int last = std::min(end, begin + (c + 1) * chunk);
    for (int i = begin + c * chunk; i < last; ++i) sum += body(i);
    partials[c] = sum;
  });
  Value total{};
  for (int c = 0; c < num_chunks; ++c) total += partials[c];
  return total;
}

}  // namespace deformable_sim::core
