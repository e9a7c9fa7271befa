// A measurement's stamp maps to the simulated instant the node was at then, across the places
// where the node's reckoning started again.
#include <gtest/gtest.h>

#include <cstdint>

#include "deformable_sim/identify/session_clock.h"

using deformable_sim::identify::SessionClock;

namespace {
constexpr std::int64_t kSecond = 1'000'000'000;
constexpr std::int64_t kStart = 1000 * kSecond;
}  // namespace

TEST(SessionClock, StampsMapToTheInstantsOfTheLatestRecordedOutputBeforeThem) {
  SessionClock clock;
  EXPECT_TRUE(clock.empty());
  EXPECT_FALSE(clock.timeAt(kStart).has_value());
  // States every 10 ms from 1000 s; after step 100 the node fell 2 s behind and started its
  // reckoning again: step 101 is stamped at 1003.01 s, not 1001.01 s. Given out of order, as a
  // bag's topics interleave.
  for (int step = 101; step <= 200; ++step)
    clock.add(kStart + 2 * kSecond + step * 10'000'000, step * 0.01);
  for (int step = 3; step <= 100; ++step) clock.add(kStart + step * 10'000'000, step * 0.01);
  EXPECT_FALSE(clock.timeAt(kStart - 1).has_value());  // before the episode
  EXPECT_NEAR(*clock.timeAt(kStart), 0.0, 1e-15);      // before the first output, back from it
  EXPECT_DOUBLE_EQ(*clock.timeAt(kStart + 505'000'000), 0.505);  // a sensor between two states
  EXPECT_DOUBLE_EQ(*clock.timeAt(kStart + 2 * kSecond + 1'010'000'000), 1.01);
  // In the gap the clock ran on and simulated time did not: no later than the next state.
  EXPECT_DOUBLE_EQ(*clock.timeAt(kStart + 2 * kSecond), 1.01);
  EXPECT_DOUBLE_EQ(*clock.timeAt(kStart + 1'005'000'000), 1.005);
  // With its last state recorded, the session ends there: a sensor's later samples are outside.
  clock.endAt(kStart + 2 * kSecond + 2'000'000'000);
  EXPECT_DOUBLE_EQ(*clock.timeAt(kStart + 4 * kSecond), 2.0);
  EXPECT_FALSE(clock.timeAt(kStart + 4 * kSecond + 1).has_value());
}
