// The node's timer callbacks step the ticks they missed, within bounds, and no more.
#include <gtest/gtest.h>

#include <vector>

#include "deformable_sim/core/driver/tick_pacer.h"

using deformable_sim::core::TickPacer;

namespace {

constexpr double kPeriod = 0.01;  // s

// Ticks stepped at each callback time.
std::vector<int> ticksAt(TickPacer& pacer, const std::vector<double>& times) {
  std::vector<int> ticks;
  for (double t : times) ticks.push_back(pacer.ticksDue(t));
  return ticks;
}

}  // namespace

TEST(TickPacer, OnTimeOrJitteryCallbacksStepOneTickEach) {
  TickPacer pacer(kPeriod);
  // Up to 0.4 of a period early or late.
  EXPECT_EQ(ticksAt(pacer, {10.0, 10.014, 10.0161, 10.034, 10.036, 10.05}),
            (std::vector<int>{1, 1, 1, 1, 1, 1}));
}

TEST(TickPacer, ALateCallbackStepsTheTicksMissedAndTheScheduleHolds) {
  TickPacer pacer(kPeriod);
  // A step ran 33 ms: the timer calls back at 43 ms, and roscpp's schedule starts again from
  // there (53, 63 ms): the two ticks missed are stepped at 43 and 53 ms, one more each.
  EXPECT_EQ(ticksAt(pacer, {0.0, 0.01, 0.043, 0.053, 0.063, 0.073}),
            (std::vector<int>{1, 1, 2, 2, 1, 1}));
}

TEST(TickPacer, ACallbackTakesAtMostKMostTicksAndTheRestLater) {
  TickPacer pacer(kPeriod);
  // 40 ms late: four ticks owed at 50 ms, paid back one a callback over and above its own.
  EXPECT_EQ(ticksAt(pacer, {0.0, 0.05, 0.06, 0.07, 0.08, 0.09}),
            (std::vector<int>{1, 2, 2, 2, 2, 1}));
}

TEST(TickPacer, ADebtLongerThanKForgiveAfterIsDropped) {
  TickPacer pacer(kPeriod);
  // A stall of half a second: stepped as one tick, and the schedule starts again there.
  EXPECT_EQ(ticksAt(pacer, {0.0, 0.01, 0.51, 0.52, 0.53}), (std::vector<int>{1, 1, 1, 1, 1}));
}

TEST(TickPacer, AClockThatGoesBackOrARestartStartsAgain) {
  TickPacer pacer(kPeriod);
  EXPECT_EQ(ticksAt(pacer, {5.0, 5.01, 1.0, 1.01}), (std::vector<int>{1, 1, 1, 1}));
  // Set back to a time after the schedule began (a test's clock started again): from there.
  EXPECT_EQ(ticksAt(pacer, {1.02, 1.03, 1.04, 1.011, 1.021}), (std::vector<int>{1, 1, 1, 1, 1}));
  pacer.restart(0.02);  // paused for a while, and now at 50 Hz
  EXPECT_EQ(ticksAt(pacer, {9.0, 9.02, 9.04, 9.08}), (std::vector<int>{1, 1, 1, 2}));
}

TEST(TickPacer, ACoarseClockFiresTheTimerSeveralTimesAndStepsOnlyItsTime) {
  TickPacer pacer(kPeriod);
  // A clock of 50 ms ticks: the timer called five times at each; five steps in all each time.
  EXPECT_EQ(ticksAt(pacer, {2.0, 2.05, 2.05, 2.05, 2.05, 2.05, 2.1, 2.1, 2.1, 2.1, 2.1}),
            (std::vector<int>{1, 2, 2, 1, 0, 0, 2, 2, 1, 0, 0}));
}

TEST(TickPacer, ACallbackAheadOfTheScheduleMovesIt) {
  TickPacer pacer(kPeriod);
  // After a late callback (35.1 ms) the timer's schedule is half a period off: a callback that
  // comes a little early owes nothing, and the schedule moves to it: one a tick from there.
  EXPECT_EQ(ticksAt(pacer, {0.0, 0.01, 0.0351, 0.0451, 0.0549, 0.0651, 0.0749, 0.0852}),
            (std::vector<int>{1, 1, 2, 2, 0, 1, 1, 1}));
}
