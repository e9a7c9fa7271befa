// What one core of the machine does at best, the floor a kernel's bytes and flops put under its
// time: reading an array that stays in one level of the cache hierarchy, and multiply-adds with
// nothing to wait for. Both four doubles wide (AVX2) where the processor has it.
#pragma once

#include <cstddef>

namespace deformable_sim::perf {

/// The sum of `count` doubles (a multiple of 16), read four-wide with four accumulators.
double sumArray(const double* values, std::size_t count);

/// `rounds` rounds of eight independent four-wide multiply-adds x <- x a + b (64 flops a round
/// with FMA; the same arithmetic in scalar code without AVX2); returns a lane, to be kept.
double multiplyAddChains(long rounds);

/// Flops multiplyAddChains does a round.
constexpr double kFlopsPerRound = 64.0;

}  // namespace deformable_sim::perf
