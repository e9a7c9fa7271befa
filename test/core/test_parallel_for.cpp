// Loops split over threads (in static chunks, or an index to the next free thread): every index
// visited once whatever the thread count, and chunked sums
// that give the same bits on any number of threads (built with OpenMP, as the library is).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <utility>
#include <vector>

#include "deformable_sim/core/base/parallel_for.h"

namespace dc = deformable_sim::core;

namespace {

// Terms whose sum depends on the order of addition: large ones that cancel, small ones between.
double awkwardTerm(int i) {
  return (i % 3 == 0 ? 1e16 : i % 3 == 1 ? -1e16 : 1.0) * (1.0 + 1e-3 * (i % 7)) + 0.1 * i;
}

}  // namespace

TEST(ParallelFor, VisitsEveryIndexOfTheRangeExactlyOnce) {
  for (int threads : {1, 2, 3, 4, 8}) {
    for (auto [begin, end] : {std::pair{0, 0}, std::pair{0, 1}, std::pair{5, 6}, std::pair{3, 1000},
                              std::pair{-7, 13}}) {
      std::vector<std::atomic<int>> visits(1100);
      dc::parallelFor(threads, begin, end, [&](int i) { ++visits[i + 10]; });
      for (int i = -10; i < 1090; ++i) {
        EXPECT_EQ(visits[i + 10].load(), (i >= begin && i < end) ? 1 : 0)
            << threads << " threads, [" << begin << ", " << end << "), index " << i;
      }
    }
  }
}

TEST(ParallelForEach, VisitsEveryIndexOnceWhateverEachCosts) {
  for (int threads : {1, 2, 3}) {
    std::vector<std::atomic<int>> visits(40);
    std::vector<double> results(40, 0.0);
    dc::parallelForEach(threads, 0, 40, [&](int i) {
      double sum = 0.0;  // uneven work: index i costs i^2 terms
      for (int k = 0; k < i * i * 50; ++k) sum += 1.0 / (k + 1.0);
      results[i] = sum;
      ++visits[i];
    });
    for (int i = 0; i < 40; ++i) {
      EXPECT_EQ(visits[i].load(), 1) << threads << " threads, index " << i;
      double sum = 0.0;
      for (int k = 0; k < i * i * 50; ++k) sum += 1.0 / (k + 1.0);
      EXPECT_EQ(results[i], sum) << threads << " threads, index " << i;  // the same bits
    }
    int calls = 0;
    dc::parallelForEach(threads, 5, 5, [&](int) { ++calls; });
    EXPECT_EQ(calls, 0);
  }
}

TEST(ParallelFor, AnEmptyOrReversedRangeCallsNothing) {
  for (int threads : {1, 4}) {
    int calls = 0;
    dc::parallelFor(threads, 10, 10, [&](int) { ++calls; });
    dc::parallelFor(threads, 10, 3, [&](int) { ++calls; });
    EXPECT_EQ(calls, 0);
  }
}

TEST(ParallelChunkedSum, SumsAsTheClosedForm) {
  // sum of i for i in [begin, end) = (end - begin)(begin + end - 1) / 2, exact in doubles here.
  std::vector<double> partials;
  for (int threads : {1, 2, 3}) {
    for (int chunk : {1, 7, 64, 5000}) {
      EXPECT_EQ(dc::parallelChunkedSum(threads, 11, 4000, chunk, partials,
                                       [](int i) { return static_cast<double>(i); }),
                (4000.0 - 11.0) * (11.0 + 4000.0 - 1.0) / 2.0)
          << threads << " threads, chunk " << chunk;
    }
  }
  EXPECT_EQ(dc::parallelChunkedSum(4, 5, 5, 3, partials, [](int) { return 1.0; }), 0.0);
}

TEST(ParallelChunkedSum, TheSameBitsOnAnyNumberOfThreads) {
  std::vector<double> partials;
  const double one_thread = dc::parallelChunkedSum(1, 0, 10001, 64, partials, awkwardTerm);
  // The order matters for these terms: summed one by one in index order the bits differ.
  double in_order = 0.0;
  for (int i = 0; i < 10001; ++i) in_order += awkwardTerm(i);
  ASSERT_NE(in_order, one_thread) << "the terms do not show the order of the sum";
  for (int threads : {2, 3, 4, 7, 16}) {
    std::vector<double> own_partials;
    EXPECT_EQ(dc::parallelChunkedSum(threads, 0, 10001, 64, own_partials, awkwardTerm), one_thread)
        << threads << " threads";
  }
  // And it is what the documented order gives: each chunk's sum in index order, the chunks' sums
  // in chunk order.
  double by_chunks = 0.0;
  for (int first = 0; first < 10001; first += 64) {
    double chunk = 0.0;
    for (int i = first; i < std::min(first + 64, 10001); ++i) chunk += awkwardTerm(i);
    by_chunks += chunk;
  }
  EXPECT_EQ(one_thread, by_chunks);
}

TEST(ParallelChunkedSum, PartialsGrowOnceAndAreNotShrunk) {
  std::vector<double> partials;
  dc::parallelChunkedSum(2, 0, 100, 10, partials, [](int) { return 1.0; });
  EXPECT_EQ(partials.size(), 10u);
  EXPECT_EQ(dc::parallelChunkedSum(2, 0, 25, 10, partials, [](int) { return 1.0; }), 25.0);
  EXPECT_EQ(partials.size(), 10u);  // three chunks needed, the ten kept
  EXPECT_EQ(dc::parallelChunkedSum(2, 0, 101, 10, partials, [](int) { return 2.0; }), 202.0);
  EXPECT_EQ(partials.size(), 11u);
}

TEST(ParallelChunkedSum, SumsAnyValueWithPlusEquals) {
  // A struct of counts, as the elements' sums are: every field summed.
  struct Counts {
    int inverted = 0;
    double energy = 0.0;
    Counts& operator+=(const Counts& other) {
      inverted += other.inverted;
      energy += other.energy;
      return *this;
    }
  };
  std::vector<Counts> partials;
  const Counts total = dc::parallelChunkedSum(3, 0, 1000, 16, partials, [](int i) {
    Counts one;
    one.inverted = i % 10 == 0 ? 1 : 0;
    one.energy = 0.5;
    return one;
  });
  EXPECT_EQ(total.inverted, 100);
  EXPECT_EQ(total.energy, 500.0);
}
