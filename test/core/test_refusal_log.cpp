// Refused messages: every one counted, a warning a second per topic.
#include <gtest/gtest.h>

#include <string>

#include "deformable_sim/core/driver/refusal_log.h"

namespace deformable_sim::core {
namespace {

TEST(RefusalLog, CountsEveryRefusalAndWarnsOnceASecondPerTopic) {
  RefusalLog log;
  EXPECT_EQ(log.refuse("~wrench", "NaN", 10.0), "~wrench: NaN (message dropped)");
  EXPECT_EQ(log.refuse("~wrench", "NaN", 10.2), "");
  EXPECT_EQ(log.refuse("~wrench", "huge", 10.4), "");
  EXPECT_NE(log.refuse("~grasp", "unknown frame", 10.5), "");  // another topic: not throttled
  EXPECT_EQ(log.refuse("~wrench", "NaN", 11.1),
            "~wrench: NaN (message dropped; 2 more dropped on ~wrench since the last warning)");
  EXPECT_EQ(log.count(), 5u);
  EXPECT_EQ(log.last(), "~wrench: NaN");
}

}  // namespace
}  // namespace deformable_sim::core
