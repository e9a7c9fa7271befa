// Whether two triangles cross, the kernel of the self-intersection check: through, not touching.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

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

TEST(TrianglesCross, NeighboursOfAFlatStripTurnedIntoPlaceDoNotCrossByRoundOff) {
  // Two triangles of a rounded side strip (the shipped sponge's), one on either side of y = 0,
  // meeting there only at points: a corner of each. Turned about z as a scene places a body
  // (a quarter turn to 7 digits), their corners lie within round-off of each other's planes.
  const Eigen::Vector3d a0(-0.0349844212, -0.00833333283, 0.0380009739),
      a1(-0.0350000004, -0.00833333283, 0.0405000001), a2(-0.0350000001, 0.0, 0.0405000001),
      b0(-0.034984421, 0.0, 0.0380009739), b1(-0.0349999999, 0.00833333471, 0.0405000001),
      b2(-0.0349844208, 0.00833333471, 0.0380009739);
  for (double angle : {0.0, 1.5707963, 0.3, 2.0, -1.1}) {
    const Eigen::Matrix3d r = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    EXPECT_FALSE(dc::trianglesCross(r * a0, r * a1, r * a2, r * b0, r * b1, r * b2)) << angle;
  }
  // A flat triangle through the first one's middle does cross it.
  EXPECT_TRUE(dc::trianglesCross(a0, a1, a2, {-0.04, -0.007, 0.039}, {-0.03, -0.007, 0.039},
                                 {-0.035, 0.004, 0.039}));
}
