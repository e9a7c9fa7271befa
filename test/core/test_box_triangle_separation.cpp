// The least translation that takes a triangle out of a box, against cases worked by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "deformable_sim/core/geometry/box_triangle_separation.h"

namespace dc = deformable_sim::core;

namespace {

const Eigen::Vector3d kCube(2.0, 2.0, 2.0);  // m, centred on the origin

Eigen::Isometry3d turnedAboutY(double angle, const Eigen::Vector3d& at) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()).toRotationMatrix();
  pose.translation() = at;
  return pose;
}

}  // namespace

TEST(BoxTriangleSeparation, AFlatTriangleAboveTheBoxIsAGapAlongItsNormal) {
  const dc::BoxTriangleSeparation s = dc::separateFromBox(
      Eigen::Isometry3d::Identity(), kCube, {-3, -3, 1.25}, {3, -3, 1.25}, {0, 3, 1.25});
  EXPECT_NEAR(s.depth, -0.25, 1e-12);
  EXPECT_NEAR(s.direction.z(), 1.0, 1e-12);
}

TEST(BoxTriangleSeparation, AFaceSunkOntoTheBoxLeavesByItsOwnSide) {
  // A wide triangle 0.1 m below the top face: out upwards by 0.1, not downwards by 2.1.
  const dc::BoxTriangleSeparation s = dc::separateFromBox(Eigen::Isometry3d::Identity(), kCube,
                                                          {-3, -3, 0.9}, {3, -3, 0.9}, {0, 3, 0.9});
  EXPECT_NEAR(s.depth, 0.1, 1e-12);
  EXPECT_NEAR(s.direction.z(), 1.0, 1e-12);
}

TEST(BoxTriangleSeparation, AnEdgePressedIntoAFaceBetweenItsCornersPushesTheFaceAway) {
  // A cube turned 45 degrees about y, its lowest edge (along y) 0.05 m above z = 0 before it is
  // lowered: a triangle in z = 0 whose corners all stay outside the cube is pressed by that
  // edge alone, 0.05 m deep, and leaves downwards.
  const double edge_below = std::sqrt(2.0);  // the centre's height above the lowest edge
  const dc::BoxTriangleSeparation s =
      dc::separateFromBox(turnedAboutY(M_PI / 4, {0.0, 0.0, edge_below - 0.05}), kCube,
                          {-0.5, -3, 0}, {0.5, -3, 0}, {0, 3, 0});
  EXPECT_NEAR(s.depth, 0.05, 1e-12);
  EXPECT_NEAR(s.direction.z(), -1.0, 1e-12);
}

TEST(BoxTriangleSeparation, ACornerThroughATriangleIsFoundAndSoIsItsGap) {
  // A cube standing on a corner  pokes 0.02 m through a triangle;
  // the same triangle lifted 0.03 m clear of that corner is 0.03 m away along its normal.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d(1, 1, 1), Eigen::Vector3d::UnitZ())
          .toRotationMatrix();
  const double lowest = std::sqrt(3.0);  // the corner (-1, -1, -1) below the centre
  ASSERT_NEAR((pose.linear() * Eigen::Vector3d(-1, -1, -1)).z(), -lowest, 1e-12);
  pose.translation() = Eigen::Vector3d(0, 0, lowest - 0.02);
  const Eigen::Vector3d a(-0.3, -0.3, 0), b(0.3, -0.3, 0), c(0, 0.4, 0);
  dc::BoxTriangleSeparation s = dc::separateFromBox(pose, kCube, a, b, c);
  EXPECT_NEAR(s.depth, 0.02, 1e-12);
  EXPECT_NEAR(s.direction.z(), -1.0, 1e-12);
  const Eigen::Vector3d lift(0, 0, -0.05);
  s = dc::separateFromBox(pose, kCube, a + lift, b + lift, c + lift);
  EXPECT_NEAR(s.depth, -0.03, 1e-12);
}

TEST(BoxTriangleSeparation, ATriangleThroughTheMiddleLeavesTheShortestWay) {
  // A small triangle inside, nearer the +x face: out through it, by its way to that face.
  const dc::BoxTriangleSeparation s = dc::separateFromBox(
      Eigen::Isometry3d::Identity(), kCube, {0.7, 0.0, 0.0}, {0.8, 0.1, 0.0}, {0.8, 0.0, 0.1});
  EXPECT_NEAR(s.depth, 1.0 - 0.7, 1e-12);
  EXPECT_NEAR(s.direction.x(), 1.0, 1e-12);
}
