// Outputs are stamped with the clock time of the simulated instant they show: exactly the
// episode's start plus the simulated time, until the clock and the steps part by more than a
// quarter of a second.
#include <gtest/gtest.h>

#include <cstdint>

#include "deformable_sim/core/driver/simulated_instants.h"

using deformable_sim::core::SimulatedInstants;

namespace {

constexpr std::int64_t kSecond = 1'000'000'000;
constexpr std::int64_t kStart = 1'700'000'000 * kSecond;  // a wall clock's time, ns
constexpr double kDt = 0.01;                              // s

}  // namespace

TEST(SimulatedInstants, StepsOnAJitteryClockAreStampedAtTheirInstantsToTheNanosecond) {
  SimulatedInstants instants;
  instants.startEpisode(kStart);
  double time = 0.0;
  // Callbacks up to 4 ms late, one 30 ms late that steps two ticks.
  const std::int64_t late_ms[] = {3, 1, 4, 30, 2, 0, 3};
  const int ticks[] = {1, 1, 1, 2, 1, 1, 1};
  int steps = 0;
  for (int k = 0; k < 7; ++k) {
    steps += ticks[k];
    time += ticks[k] * kDt;
    const std::int64_t now = kStart + steps * (kSecond / 100) + late_ms[k] * 1'000'000;
    EXPECT_FALSE(instants.stepped(time, now)) << k;
    EXPECT_EQ(instants.stamp(time), kStart + steps * (kSecond / 100)) << k;
  }
  EXPECT_EQ(instants.start(), kStart);
}

TEST(SimulatedInstants, APauseOrASlowSceneStartsTheReckoningAgainAtTheClock) {
  SimulatedInstants instants;
  instants.startEpisode(kStart);
  EXPECT_FALSE(instants.stepped(1.0, kStart + kSecond));
  // Paused for 5 s: while paused the state shows instant 1 s, still at its stamp; the first
  // step after it is at the clock.
  EXPECT_EQ(instants.stamp(1.0), kStart + kSecond);
  EXPECT_TRUE(instants.stepped(1.01, kStart + 6 * kSecond + 10'000'000));
  EXPECT_EQ(instants.stamp(1.01), kStart + 6 * kSecond + 10'000'000);
  EXPECT_EQ(instants.start(), kStart + 5 * kSecond);
  // Behind by 0.25 s exactly is still on the reckoning; by more, not.
  EXPECT_FALSE(instants.stepped(1.02, instants.stamp(1.02) + SimulatedInstants::kMostLagNs));
  EXPECT_TRUE(instants.stepped(1.03, instants.stamp(1.03) + SimulatedInstants::kMostLagNs + 1));
}

TEST(SimulatedInstants, AClockThatWentBackStartsTheReckoningAgainAndAnEpisodeAtItsStart) {
  SimulatedInstants instants;
  instants.startEpisode(kStart);
  // A looped bag's clock: the instants would be a minute in its future.
  EXPECT_TRUE(instants.stepped(60.0, kStart + kSecond));
  EXPECT_EQ(instants.stamp(60.0), kStart + kSecond);
  instants.startEpisode(kStart + 2 * kSecond);  // a reset
  EXPECT_EQ(instants.stamp(0.0), kStart + 2 * kSecond);
  EXPECT_EQ(instants.stamp(0.5), kStart + 2 * kSecond + kSecond / 2);
}
