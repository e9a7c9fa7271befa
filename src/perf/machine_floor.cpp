#include "deformable_sim/perf/machine_floor.h"

#include "deformable_sim/core/base/cpu_features.h"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace deformable_sim::perf {

namespace {

double sumArrayPortable(const double* values, std::size_t count) {
  double sums[4] = {0.0, 0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < count; i += 4) {
    for (int l = 0; l < 4; ++l) sums[l] += values[i + l];
  }
  return sums[0] + sums[1] + sums[2] + sums[3];
}

double chainsPortable(long rounds) {
  double x[32];
  for (double& v : x) v = 1.0;
  for (long r = 0; r < rounds; ++r) {
    for (double& v : x) v = v * 0.999999 + 1e-7;
  }
  return x[0];
}

#if defined(__x86_64__)
__attribute__((target("avx2,fma"))) double sumArrayAvx2(const double* values, std::size_t count) {
  __m256d s0 = _mm256_setzero_pd(), s1 = s0, s2 = s0, s3 = s0;
  for (std::size_t i = 0; i < count; i += 16) {
    s0 = _mm256_add_pd(s0, _mm256_loadu_pd(values + i));
    s1 = _mm256_add_pd(s1, _mm256_loadu_pd(values + i + 4));
    s2 = _mm256_add_pd(s2, _mm256_loadu_pd(values + i + 8));
    s3 = _mm256_add_pd(s3, _mm256_loadu_pd(values + i + 12));
  }
  double lanes[4];
  _mm256_storeu_pd(lanes, _mm256_add_pd(_mm256_add_pd(s0, s1), _mm256_add_pd(s2, s3)));
  return lanes[0] + lanes[1] + lanes[2] + lanes[3];
}

__attribute__((target("avx2,fma"))) double chainsAvx2(long rounds) {
  __m256d x[8];
  for (__m256d& v : x) v = _mm256_set1_pd(1.0);
  const __m256d a = _mm256_set1_pd(0.999999), b = _mm256_set1_pd(1e-7);
  for (long r = 0; r < rounds; ++r) {
    for (__m256d& v : x) v = _mm256_fmadd_pd(v, a, b);
  }
  double lanes[4];
  _mm256_storeu_pd(lanes, x[0]);
  return lanes[0];
}
#endif

}  // namespace

double sumArray(const double* values, std::size_t count) {
#if defined(__x86_64__)
  if (core::hasAvx2Fma()) return sumArrayAvx2(values, count);
#endif
  return sumArrayPortable(values, count);
}

double multiplyAddChains(long rounds) {
#if defined(__x86_64__)
  if (core::hasAvx2Fma()) return chainsAvx2(rounds);
#endif
  return chainsPortable(rounds);
}

}  // namespace deformable_sim::perf
