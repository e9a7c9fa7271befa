// The least translation that takes a triangle out of a box, out of another triangle, and out of
// the triangle of a mesh it overlaps most, against cases worked by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "deformable_sim/core/geometry/triangle_mesh.h"
#include "deformable_sim/core/geometry/triangle_mesh_shape.h"
#include "deformable_sim/core/geometry/triangle_separation.h"

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

TEST(TriangleSeparation, AFlatTriangleAboveTheBoxIsAGapAlongItsNormal) {
  const dc::TriangleSeparation s = dc::separateFromBox(Eigen::Isometry3d::Identity(), kCube,
                                                       {-3, -3, 1.25}, {3, -3, 1.25}, {0, 3, 1.25});
  EXPECT_NEAR(s.depth, -0.25, 1e-12);
  EXPECT_NEAR(s.direction.z(), 1.0, 1e-12);
}

TEST(TriangleSeparation, AFaceSunkOntoTheBoxLeavesByItsOwnSide) {
  // A wide triangle 0.1 m below the top face: out upwards by 0.1, not downwards by 2.1.
  const dc::TriangleSeparation s = dc::separateFromBox(Eigen::Isometry3d::Identity(), kCube,
                                                       {-3, -3, 0.9}, {3, -3, 0.9}, {0, 3, 0.9});
  EXPECT_NEAR(s.depth, 0.1, 1e-12);
  EXPECT_NEAR(s.direction.z(), 1.0, 1e-12);
}

TEST(TriangleSeparation, AnEdgePressedIntoAFaceBetweenItsCornersPushesTheFaceAway) {
  // A cube turned 45 degrees about y, its lowest edge (along y) 0.05 m above z = 0 before it is
  // lowered: a triangle in z = 0 whose corners all stay outside the cube is pressed by that
  // edge alone, 0.05 m deep, and leaves downwards.
  const double edge_below = std::sqrt(2.0);  // the centre's height above the lowest edge
  const dc::TriangleSeparation s =
      dc::separateFromBox(turnedAboutY(M_PI / 4, {0.0, 0.0, edge_below - 0.05}), kCube,
                          {-0.5, -3, 0}, {0.5, -3, 0}, {0, 3, 0});
  EXPECT_NEAR(s.depth, 0.05, 1e-12);
  EXPECT_NEAR(s.direction.z(), -1.0, 1e-12);
}

TEST(TriangleSeparation, ACornerThroughATriangleIsFoundAndSoIsItsGap) {
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
  dc::TriangleSeparation s = dc::separateFromBox(pose, kCube, a, b, c);
  EXPECT_NEAR(s.depth, 0.02, 1e-12);
  EXPECT_NEAR(s.direction.z(), -1.0, 1e-12);
  const Eigen::Vector3d lift(0, 0, -0.05);
  s = dc::separateFromBox(pose, kCube, a + lift, b + lift, c + lift);
  EXPECT_NEAR(s.depth, -0.03, 1e-12);
}

TEST(TriangleSeparation, ATriangleThroughTheMiddleLeavesTheShortestWay) {
  // A small triangle inside, nearer the +x face: out through it, by its way to that face.
  const dc::TriangleSeparation s = dc::separateFromBox(
      Eigen::Isometry3d::Identity(), kCube, {0.7, 0.0, 0.0}, {0.8, 0.1, 0.0}, {0.8, 0.0, 0.1});
  EXPECT_NEAR(s.depth, 1.0 - 0.7, 1e-12);
  EXPECT_NEAR(s.direction.x(), 1.0, 1e-12);
}

TEST(TriangleSeparation, ACornerThroughAFaceDentsItAsDeepAsItReaches) {
  // An upright triangle whose lower corner pokes 0.05 m down through a level face (outward +z).
  const Eigen::Vector3d a(-1, -1, 0), b(1, -1, 0), c(0, 1, 0), down(0, 0, -1);
  EXPECT_NEAR(dc::dentDepth(a, b, c, down, {0, 0, -0.05}, {-0.5, 0, 1}, {0.5, 0, 1}), 0.05, 1e-15);
  // Lifted 0.2 m clear of it: 0.15 m in front.
  EXPECT_NEAR(dc::dentDepth(a, b, c, down, {0, 0, 0.15}, {-0.5, 0, 1.2}, {0.5, 0, 1.2}), -0.15,
              1e-15);
  // Beside its outline: no dent, however deep.
  EXPECT_EQ(dc::dentDepth(a, b, c, down, {3, 0, -0.5}, {2.5, 0, 1}, {3.5, 0, 1}),
            -std::numeric_limits<double>::infinity());
}

TEST(TriangleSeparation, OnlyThePartWithinTheFacesOutlineDents) {
  // A long sloping triangle that reaches 1 m below the face's plane far beyond its outline, and
  // 0.1 m below it at the outline's far edge (x = 1): the dent is 0.1 m.
  const Eigen::Vector3d a(-1, -1, 0), b(1, -1, 0), c(1, 1, 0), down(0, 0, -1);
  EXPECT_NEAR(dc::dentDepth(a, b, c, down, {-1, -5, 0.1}, {-1, 5, 0.1}, {10, 0, -1}), 0.1, 1e-12);
}

TEST(TriangleSeparation, AMeshDentsAFaceAsDeepAsItsEdgeReachesAlongTheFacesNormal) {
  // The cube of the box case above as a mesh of twelve triangles: its lowest edge, shared by two
  // of them, dents the level triangle 0.05 m, as deep as the primitive box presses it. Far off,
  // no triangle is near.
  const dc::TriangleMeshShape cube(dc::boxSurface(-0.5 * kCube, 0.5 * kCube));
  const Eigen::Isometry3d pose = turnedAboutY(M_PI / 4, {0.0, 0.0, std::sqrt(2.0) - 0.05});
  const Eigen::Isometry3d to_cube = pose.inverse();
  const Eigen::Vector3d a(-0.5, -3, 0), b(0.5, -3, 0), c(0, 3, 0), down(0, 0, -1);
  std::vector<int> near;
  EXPECT_NEAR(cube.dent(to_cube * a, to_cube * b, to_cube * c, to_cube.linear() * down, 0.0, near),
              dc::separateFromBox(pose, kCube, a, b, c).depth, 1e-12);
  const Eigen::Vector3d far(10, 0, 0);
  EXPECT_EQ(cube.dent(a + far, b + far, c + far, down, 0.1, near),
            -std::numeric_limits<double>::infinity());
}

TEST(TriangleSeparation, AMeshDentsASmallFaceDeeperThanHalfItsWidth) {
  // A bar 20 m long, turned 45 degrees about its length, its edge 0.3 m into a face 1 m wide: a
  // thin triangle of its sides is left soonest sideways past its plane, but the bar dents the
  // face 0.3 m along its normal.
  const Eigen::Vector3d size(2.0, 20.0, 2.0);
  const dc::TriangleMeshShape bar(dc::boxSurface(-0.5 * size, 0.5 * size));
  const Eigen::Isometry3d pose = turnedAboutY(M_PI / 4, {0.0, 0.0, std::sqrt(2.0) - 0.3});
  const Eigen::Isometry3d to_bar = pose.inverse();
  const Eigen::Vector3d a(-0.5, -0.5, 0), b(0.5, -0.5, 0), c(0, 0.5, 0), down(0, 0, -1);
  std::vector<int> near;
  EXPECT_NEAR(bar.dent(to_bar * a, to_bar * b, to_bar * c, to_bar.linear() * down, 0.0, near), 0.3,
              1e-12);
}

TEST(TriangleSeparation, AnEdgeAcrossAFacePressesAtTheMiddleOfItsPartWithin) {
  // A level face (the body below it: inward -z) and an edge 0.05 m below its plane, along x.
  const Eigen::Vector3d a(-1, -1, 0), b(1, -1, 0), c(0, 1, 0), inward(0, 0, -1);
  const dc::EdgeDent level = dc::edgeDent(a, b, c, inward, {-5, 0, -0.05}, {5, 0, -0.05});
  EXPECT_NEAR(level.depth, 0.05, 1e-15);
  // Within the outline from x = -0.5 to 0.5 at y = 0: its middle, not an end of the edge.
  EXPECT_LT((level.at - Eigen::Vector3d(0, 0, -0.05)).norm(), 1e-15);
  EXPECT_FALSE(level.at_corner);
  // Tilted, from 5 mm behind to 5 mm in front over that part: the deepest depth, at the middle.
  const dc::EdgeDent tilted = dc::edgeDent(a, b, c, inward, {-5, 0, -0.05}, {5, 0, 0.05});
  EXPECT_NEAR(tilted.depth, 0.005, 1e-15);
  EXPECT_LT(tilted.at.norm(), 1e-15);
  // An edge standing on the face, its lower end 0.05 m through: that end, a corner.
  const dc::EdgeDent corner = dc::edgeDent(a, b, c, inward, {0.1, 0, -0.05}, {0.1, 0, 1});
  EXPECT_NEAR(corner.depth, 0.05, 1e-15);
  EXPECT_LT((corner.at - Eigen::Vector3d(0.1, 0, -0.05)).norm(), 1e-15);
  EXPECT_TRUE(corner.at_corner);
  // Beside the outline: no dent, however deep.
  EXPECT_EQ(dc::edgeDent(a, b, c, inward, {3, -5, -0.5}, {3, 5, -0.5}).depth,
            -std::numeric_limits<double>::infinity());
}
