// Timer ticks let through once per stamp, and a new timeline (a looped bag) started again.
#include <gtest/gtest.h>

#include "deformable_sim/core/driver/once_per_stamp.h"

namespace deformable_sim::core {
namespace {

TEST(OncePerStamp, LetsEachStampThroughOnceAndANewTimelineStartAgain) {
  OncePerStamp stamps;
  EXPECT_TRUE(stamps.accept(5'000'000'000));
  EXPECT_FALSE(stamps.accept(5'000'000'000));  // the timer fired twice at one time
  EXPECT_FALSE(stamps.accept(4'990'000'000));
  EXPECT_TRUE(stamps.accept(5'010'000'000));
  EXPECT_TRUE(stamps.accept(1'000'000'000));  // a looped bag: seconds back
  EXPECT_FALSE(stamps.accept(1'000'000'000));
}

}  // namespace
}  // namespace deformable_sim::core
