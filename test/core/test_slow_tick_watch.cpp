// When the node counts as unable to keep real time.
#include <gtest/gtest.h>

#include "deformable_sim/core/driver/slow_tick_watch.h"

namespace deformable_sim::core {
namespace {

// Slow for 5 s of wall time in a row, not at one slow tick; a pause or a fast tick starts over.
TEST(SlowTickWatch, IsSlowAfterFiveSecondsUnderNineTenthsOfRealTime) {
  SlowTickWatch watch;
  for (double t = 0.0; t < 4.95; t += 0.1) {
    watch.sample(t, 0.5, true);
    ASSERT_FALSE(watch.slow()) << t;
  }
  watch.sample(5.0, 0.5, true);
  EXPECT_TRUE(watch.slow());
  EXPECT_DOUBLE_EQ(watch.slowFor(5.0), 5.0);
  watch.sample(5.1, 0.95, true);  // caught up
  EXPECT_FALSE(watch.slow());
  EXPECT_EQ(watch.slowFor(5.1), 0.0);
  for (double t = 6.0; t < 12.5; t += 1.0) watch.sample(t, 0.5, t != 9.0);
  EXPECT_FALSE(watch.slow());  // the pause at 9 s started the count again
  watch.sample(15.0, 0.5, true);
  EXPECT_TRUE(watch.slow());
  watch.sample(14.0, 0.5, true);  // the clock went back
  EXPECT_FALSE(watch.slow());
}

}  // namespace
}  // namespace deformable_sim::core
