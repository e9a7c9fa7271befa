// When an output published at its own rate is due on the ticks of the node's timer.
#include <gtest/gtest.h>

#include "deformable_sim/core/driver/periodic_schedule.h"

namespace deformable_sim::core {
namespace {

TEST(PeriodicSchedule, KeepsTheAskedRateOnTicksOfAnotherRate) {
  PeriodicSchedule schedule(1.0 / 30.0);
  int due = 0;
  for (int tick = 0; tick < 1000; ++tick) due += schedule.due(1000.0 + 0.01 * tick);
  EXPECT_NEAR(due, 300, 1);  // 10 s of 100 Hz ticks: 30 Hz, not every fourth tick (25 Hz)
}

TEST(PeriodicSchedule, NextTimeIsThePreviousOnePlusThePeriodNotTheTickPlusThePeriod) {
  PeriodicSchedule schedule(0.1);
  EXPECT_TRUE(schedule.due(0.0));  // the first call is always due
  EXPECT_FALSE(schedule.due(0.05));
  EXPECT_TRUE(schedule.due(0.15));  // a late tick: the next is due at 0.2, not at 0.25
  EXPECT_FALSE(schedule.due(0.19));
  EXPECT_TRUE(schedule.due(0.21));
}

TEST(PeriodicSchedule, StartsAgainWhenTheClockGoesBackOrStalls) {
  PeriodicSchedule schedule(0.1);
  EXPECT_TRUE(schedule.due(50.0));
  EXPECT_FALSE(schedule.due(50.05));
  EXPECT_TRUE(schedule.due(10.0));  // a looped bag
  EXPECT_FALSE(schedule.due(10.05));
  EXPECT_TRUE(schedule.due(20.0));  // a long stall: one output, not a burst of a hundred
  EXPECT_FALSE(schedule.due(20.01));
}

}  // namespace
}  // namespace deformable_sim::core
