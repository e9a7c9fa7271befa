// The tools behind case C2: the period fit on signals whose answer is known, and implicit Euler's
// linear theory against the table in the reference README (case C2).
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "deformable_sim/bench/damped_oscillation.h"
#include "deformable_sim/bench/implicit_euler_theory.h"

namespace bench = deformable_sim::bench;

TEST(DampedOscillation, RecoversTheDominantModeDespiteAFasterOne) {
  const double period = 1.5, ratio = 0.8, interval = period / 40;
  const double sigma = -std::log(ratio) / period;  // decay rate, 1/s
  std::vector<double> samples;
  for (int n = 0; n < 120; ++n) {
    const double t = n * interval;
    samples.push_back(1e-3 * std::exp(-sigma * t) * std::cos(2 * M_PI * t / period) +
                      5e-5 * std::exp(-3 * t) * std::cos(2 * M_PI * 6.2 * t + 0.4));
  }
  const bench::DampedOscillation fit = bench::fitDominantOscillation(samples, interval);
  EXPECT_NEAR(fit.period_s, period, 1e-9);
  EXPECT_NEAR(fit.amplitude_ratio_per_cycle, ratio, 1e-9);
  EXPECT_NEAR(fit.amplitude, 1e-3, 1e-9);
}

TEST(DampedOscillation, RefusesTooFewSamplesAndSignalsWithoutOscillation) {
  EXPECT_THROW(bench::fitDominantOscillation(std::vector<double>(10, 1.0), 0.1),
               std::invalid_argument);
  std::vector<double> decay;
  for (int n = 0; n < 100; ++n) decay.push_back(std::exp(-0.1 * n));
  EXPECT_THROW(bench::fitDominantOscillation(decay, 0.1, 1), std::invalid_argument);
}

// The reference README's table for f1 = 0.5092 Hz: h, period ratio, amplitude ratio per cycle.
TEST(ImplicitEulerTheory, MatchesTheReferenceTable) {
  const double omega = 2 * M_PI * 0.5092, period = 1 / 0.5092;
  const struct {
    double h, period_ratio, amplitude_ratio;
  } table[] = {{1.0 / 30, 1.00378, 0.7158},
               {1.0 / 60, 1.00095, 0.8458},
               {1.0 / 100, 1.00034, 0.9044},
               {1.0 / 1000, 1.000003, 0.9900}};
  for (const auto& row : table) {
    EXPECT_NEAR(bench::implicitEulerPeriod(omega, row.h) / period, row.period_ratio, 1e-5);
    EXPECT_NEAR(bench::implicitEulerAmplitudeRatioPerCycle(omega, row.h), row.amplitude_ratio,
                1e-4);
  }
}
