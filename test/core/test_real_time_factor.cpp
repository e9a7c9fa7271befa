// The real-time factor the node reports: simulated over clock time of the last second.
#include <gtest/gtest.h>

#include "deformable_sim/core/driver/real_time_factor.h"

namespace deformable_sim::core {
namespace {

TEST(RealTimeFactor, IsSimulatedTimeOverClockTimeOfTheLastSecond) {
  RealTimeFactor factor;
  EXPECT_EQ(factor.value(), 0.0);
  for (int k = 0; k <= 300; ++k) factor.sample(0.01 * k, 0.005 * k);
  EXPECT_NEAR(factor.value(), 0.5, 1e-9);
  factor.sample(1.0, 2.0);  // the clock went back: start again
  EXPECT_EQ(factor.value(), 0.0);
}

}  // namespace
}  // namespace deformable_sim::core
