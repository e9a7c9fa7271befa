// The node's health from a tick's status: its summary and the costliest part of a step.
#include <gtest/gtest.h>

#include <string>

#include "deformable_sim/core/driver/tick_status.h"

namespace deformable_sim::core {
namespace {

TEST(Health, WarnsOfRecoveriesMissedTolerancesAndLostRealTimeInThatOrder) {
  TickStatus status;
  status.reports.resize(1);
  status.reports[0].solve.converged = true;
  status.reports[0].inverted_elements = 3;
  status.real_time_factor = 0.03;  // but not for long yet
  status.steps = 1;
  status.step_time_s = 0.29;
  status.reports[0].times.body_contact = 0.28;
  Health h = health(status);
  EXPECT_TRUE(h.ok);
  EXPECT_EQ(h.summary, "running");
  EXPECT_EQ(h.inverted_elements, 3);
  status.slow = true;
  EXPECT_EQ(
      health(status).summary,
      "cannot keep real time (0.03 x real time): contact between bodies 280 of 290 ms a step");
  status.paused = true;
  EXPECT_EQ(health(status).summary, "paused");
  status.reports[0].solve.converged = false;
  EXPECT_EQ(health(status).summary, "a solve did not reach its tolerance");
  status.recent_recovery = true;
  h = health(status);
  EXPECT_FALSE(h.ok);
  EXPECT_EQ(h.summary, "the watchdog undid a step that left a non-finite value");
  status.recovery_from_leap = true;
  EXPECT_EQ(health(status).summary, "the watchdog undid a step whose energy leapt past its inputs");
}

// The costliest part of the last step, summed over the bodies, against the tick's time a step.
TEST(Health, NamesTheCostliestPartOfAStep) {
  TickStatus status;
  status.steps = 10;
  status.step_time_s = 0.05;  // 5 ms a step
  status.reports.resize(2);
  status.reports[0].times.rotations = 0.0005;
  status.reports[0].times.assembly = 0.0010;
  status.reports[1].times.assembly = 0.0010;
  status.reports[0].times.solve = 0.0020;
  status.reports[1].times.obstacle_contact = 0.0001;
  EXPECT_EQ(costliestPart(status), "elasticity 2.5 of 5 ms a step");
  status.reports[1].times.solve = 0.0010;
  // The bodies' parts now add up to more than the step's wall time (they step side by side).
  EXPECT_EQ(costliestPart(status), "linear solves 3 of 5.6 ms of work a step (5 ms wall)");
  status.reports[0].times.obstacle_contact = 0.0040;
  EXPECT_EQ(costliestPart(status),
            "contact with obstacles 4.1 of 9.6 ms of work a step (5 ms wall)");
}

TEST(Health, APartIsNeverToldAsMoreThanItsWhole) {
  // Two bodies stepped side by side on two threads: 19.4 ms of contact in a 19.3 ms step ("19.4
  // of 19.3 ms" was printed).
  TickStatus status;
  status.steps = 1;
  status.step_time_s = 0.0193;
  status.reports.resize(2);
  status.reports[0].times.body_contact = 0.0097;
  status.reports[1].times.body_contact = 0.0097;
  status.reports[0].times.solve = 0.0060;
  status.reports[1].times.solve = 0.0060;
  EXPECT_EQ(costliestPart(status),
            "contact between bodies 19.4 of 31.4 ms of work a step (19.3 ms wall)");
}

}  // namespace
}  // namespace deformable_sim::core
