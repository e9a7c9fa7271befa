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

TEST(TriangleSeparation, TrianglesInParallelPlanesAreAGapAlongTheirNormal) {
  const dc::TriangleSeparation s = dc::separateFromTriangle(
      {-1, -1, 0}, {1, -1, 0}, {0, 1, 0}, {-1, -1, 0.25}, {1, -1, 0.25}, {0, 1, 0.25});
  EXPECT_NEAR(s.depth, -0.25, 1e-12);
  EXPECT_NEAR(s.direction.z(), 1.0, 1e-12);
}

TEST(TriangleSeparation, ACornerThroughAFaceBetweenItsCornersPushesTheFaceAway) {
  // An upright obstacle triangle whose lower corner pokes 0.05 m down through a level face: the
  // face leaves downwards by 0.05, not sideways by half its width.
  const dc::TriangleSeparation s = dc::separateFromTriangle(
      {0, 0, -0.05}, {-0.5, 0, 1}, {0.5, 0, 1}, {-1, -1, 0}, {1, -1, 0}, {0, 1, 0});
  EXPECT_NEAR(s.depth, 0.05, 1e-12);
  EXPECT_NEAR(s.direction.z(), -1.0, 1e-12);
}

TEST(TriangleSeparation, TrianglesSideBySideInOnePlaneAreApart) {
  // In the plane z = 0, 0.5 m apart along x: every cross product of their edges lies along z, so
  // only the edges' normals within the plane part them.
  const dc::TriangleSeparation s = dc::separateFromTriangle(
      {-1, -1, 0}, {0, -1, 0}, {0, 1, 0}, {0.5, -1, 0}, {1.5, -1, 0}, {0.5, 1, 0});
  EXPECT_NEAR(s.depth, -0.5, 1e-12);
  EXPECT_NEAR(s.direction.x(), 1.0, 1e-12);
}

TEST(TriangleSeparation, AMeshAnswersForItsTriangleThatPressesDeepest) {
  // The cube of the box case above as a mesh of twelve triangles: its lowest edge, shared by two
  // of them, presses the level triangle 0.05 m down, as the primitive box does; far off, no
  // triangle is near.
  const dc::TriangleMeshShape cube(dc::boxSurface(-0.5 * kCube, 0.5 * kCube));
  const Eigen::Isometry3d pose = turnedAboutY(M_PI / 4, {0.0, 0.0, std::sqrt(2.0) - 0.05});
  const Eigen::Isometry3d to_cube = pose.inverse();
  const Eigen::Vector3d a(-0.5, -3, 0), b(0.5, -3, 0), c(0, 3, 0);
  std::vector<int> near;
  const dc::TriangleSeparation s =
      cube.separation(to_cube * a, to_cube * b, to_cube * c, 0.0, near);
  const dc::TriangleSeparation box = dc::separateFromBox(pose, kCube, a, b, c);
  EXPECT_NEAR(s.depth, box.depth, 1e-12);
  EXPECT_NEAR((pose.linear() * s.direction).z(), -1.0, 1e-12);
  const Eigen::Vector3d far(10, 0, 0);
  EXPECT_EQ(cube.separation(a + far, b + far, c + far, 0.1, near).depth,
            -std::numeric_limits<double>::infinity());
}
