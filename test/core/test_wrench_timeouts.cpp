// Wrenches whose source fell silent lapse.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "deformable_sim/core/driver/wrench_timeouts.h"

namespace deformable_sim::core {
namespace {

TEST(WrenchTimeouts, ASilentSourceLapsesAndAZeroWrenchIsForgotten) {
  WrenchTimeouts timeouts(0.5);
  timeouts.heard("a", 1.0, false);
  timeouts.heard("b", 1.2, false);
  timeouts.heard("b", 1.3, true);  // b cleared its own wrench
  EXPECT_TRUE(timeouts.expire(1.4).empty());
  EXPECT_EQ(timeouts.expire(1.6), std::vector<std::string>{"a"});
  EXPECT_TRUE(timeouts.expire(9.0).empty());
  WrenchTimeouts never;
  never.heard("a", 0.0, false);
  EXPECT_TRUE(never.expire(1e9).empty());
}

}  // namespace
}  // namespace deformable_sim::core
