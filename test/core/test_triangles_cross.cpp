// Whether two triangles cross, the kernel of the self-intersection check: through, not touching.
#include <gtest/gtest.h>

#include "deformable_sim/core/geometry/triangles_cross.h"

namespace dc = deformable_sim::core;

namespace {

// A triangle in the plane z = 0 around the origin.
const Eigen::Vector3d kA0(-1, -1, 0), kA1(1, -1, 0), kA2(0, 1, 0);

bool crossesA(const Eigen::Vector3d& b0, const Eigen::Vector3d& b1, const Eigen::Vector3d& b2) {
  return dc::trianglesCross(kA0, kA1, kA2, b0, b1, b2);
}

}  // namespace

TEST(TrianglesCross, ATrianglePiercingTheOtherCrossesItBothWaysRound) {
  const Eigen::Vector3d b0(0, -0.2, -1), b1(0, -0.2, 1), b2(0, 3, 0);
  EXPECT_TRUE(crossesA(b0, b1, b2));
  EXPECT_TRUE(dc::trianglesCross(b0, b1, b2, kA0, kA1, kA2));
  EXPECT_TRUE(crossesA(b1, b0, b2));  // whatever the winding
}

TEST(TrianglesCross, ApartOrOnlyThePlaneCrossedDoNotCross) {
  EXPECT_FALSE(crossesA({0, 0, 1}, {1, 0, 2}, {0, 1, 2}));  // wholly above
  // Through the plane z = 0, but outside the triangle.
  EXPECT_FALSE(crossesA({5, 0, -1}, {5, 0, 1}, {6, 1, 0}));
}

TEST(TrianglesCross, TouchingOrOverlappingInOnePlaneDoesNotCount) {
  EXPECT_FALSE(crossesA(kA0, {-1, -1, 1}, {-2, 0, 1}));                  // a shared corner
  EXPECT_FALSE(crossesA({0, 0, 0}, {0, 0, 1}, {1, 1, 1}));               // a corner on the inside
  EXPECT_FALSE(crossesA({-1, -1, 0}, {1, -1, 0}, {0, -2, 1}));           // a shared side
  EXPECT_FALSE(crossesA({-0.5, -0.5, 0}, {0.5, -0.5, 0}, {0, 0.5, 0}));  // in one plane
}
