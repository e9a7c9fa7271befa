// The analytic shapes' signed distances (box, sphere, cylinder) against their closed forms, the
// consistency of distance, nearest point and normal, the distance's gradient, and the messages
// validation gives.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "deformable_sim/core/geometry/shape.h"
#include "thrown_message.h"

namespace dc = deformable_sim::core;
namespace dt = deformable_sim::test;

namespace {

dc::Shape box(const Eigen::Vector3d& size) {
  dc::Shape shape;
  shape.kind = dc::Shape::Kind::kBox;
  shape.size = size;
  return shape;
}

dc::Shape sphere(double radius) {
  dc::Shape shape;
  shape.kind = dc::Shape::Kind::kSphere;
  shape.radius = radius;
  return shape;
}

dc::Shape cylinder(double radius, double length) {
  dc::Shape shape;
  shape.kind = dc::Shape::Kind::kCylinder;
  shape.radius = radius;
  shape.length = length;
  return shape;
}

// For points around `shape`: the nearest point lies on the surface (distance 0 there), the point
// is the nearest point moved by the distance along the unit normal, and away from edges and the
// medial axis the normal is the distance's gradient.
void expectConsistent(const dc::Shape& shape, double extent, int seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> coordinate(-extent, extent);
  const double h = 1e-6;
  for (int k = 0; k < 500; ++k) {
    const Eigen::Vector3d p(coordinate(random), coordinate(random), coordinate(random));
    Eigen::Vector3d surface, normal;
    const double d = dc::signedDistance(shape, p, &surface, &normal);
    EXPECT_NEAR(normal.norm(), 1.0, 1e-12) << p.transpose();
    EXPECT_NEAR((surface + d * normal - p).norm(), 0.0, 1e-12) << p.transpose();
    EXPECT_NEAR(dc::signedDistance(shape, surface), 0.0, 1e-12) << p.transpose();
    // The gradient by central differences, where it is smooth (both sides agree to h).
    Eigen::Vector3d gradient;
    for (int a = 0; a < 3; ++a) {
      const Eigen::Vector3d step = h * Eigen::Vector3d::Unit(a);
      gradient[a] =
          (dc::signedDistance(shape, p + step) - dc::signedDistance(shape, p - step)) / (2.0 * h);
    }
    if (std::abs(gradient.norm() - 1.0) < 1e-6) {
      EXPECT_NEAR((gradient - normal).norm(), 0.0, 1e-6) << p.transpose();
    }
  }
}

}  // namespace

TEST(Shape, SphereDistanceIsTheDistanceFromTheCentreLessTheRadius) {
  const dc::Shape ball = sphere(0.5);
  Eigen::Vector3d surface, normal;
  EXPECT_NEAR(dc::signedDistance(ball, {3.0, 4.0, 0.0}, &surface, &normal), 4.5, 1e-15);
  EXPECT_NEAR((surface - Eigen::Vector3d(0.3, 0.4, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((normal - Eigen::Vector3d(0.6, 0.8, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(dc::signedDistance(ball, {0.0, 0.0, -0.2}, &surface, &normal), -0.3, 1e-15);
  EXPECT_EQ(normal, Eigen::Vector3d(0, 0, -1));
  // At the centre every direction is nearest: one is chosen, at the full depth.
  EXPECT_EQ(dc::signedDistance(ball, Eigen::Vector3d::Zero(), &surface, &normal), -0.5);
  EXPECT_NEAR(normal.norm(), 1.0, 1e-15);
  EXPECT_NEAR((surface - 0.5 * normal).norm(), 0.0, 1e-15);
  expectConsistent(ball, 1.0, 1);
}

TEST(Shape, BoxDistanceOutsideIsToTheNearestFaceEdgeOrCorner) {
  const dc::Shape block = box({2.0, 1.0, 0.5});  // half sizes 1, 0.5, 0.25
  Eigen::Vector3d surface, normal;
  // Beside a face.
  EXPECT_NEAR(dc::signedDistance(block, {1.5, 0.1, -0.1}, &surface, &normal), 0.5, 1e-15);
  EXPECT_EQ(normal, Eigen::Vector3d(1, 0, 0));
  // Beyond an edge (x and y both out): the distance to the edge.
  EXPECT_NEAR(dc::signedDistance(block, {1.3, -0.9, 0.0}, &surface, &normal), 0.5, 1e-15);
  EXPECT_NEAR((surface - Eigen::Vector3d(1.0, -0.5, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((normal - Eigen::Vector3d(0.6, -0.8, 0.0)).norm(), 0.0, 1e-15);
  // Beyond a corner.
  EXPECT_NEAR(dc::signedDistance(block, {-2.0, 2.5, -2.25}), std::sqrt(1.0 + 4.0 + 4.0), 1e-15);
  expectConsistent(block, 2.0, 2);
}

TEST(Shape, BoxDistanceInsideIsToTheNearestFace) {
  const dc::Shape block = box({2.0, 1.0, 0.5});
  Eigen::Vector3d surface, normal;
  EXPECT_NEAR(dc::signedDistance(block, {0.9, 0.0, 0.0}, &surface, &normal), -0.1, 1e-15);
  EXPECT_EQ(normal, Eigen::Vector3d(1, 0, 0));
  EXPECT_NEAR((surface - Eigen::Vector3d(1.0, 0.0, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(dc::signedDistance(block, {0.0, 0.0, -0.2}, &surface, &normal), -0.05, 1e-15);
  EXPECT_EQ(normal, Eigen::Vector3d(0, 0, -1));
  // At the centre: the thinnest direction, half of the smallest size.
  EXPECT_EQ(dc::signedDistance(block, Eigen::Vector3d::Zero(), &surface, &normal), -0.25);
  EXPECT_EQ(std::abs(normal.z()), 1.0);
  // Never deeper than that anywhere.
  std::mt19937 random(4);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d p(unit(random), 0.5 * unit(random), 0.25 * unit(random));
    const double d = dc::signedDistance(block, p);
    EXPECT_LE(d, 0.0);
    EXPECT_GE(d, -0.25);
    const Eigen::Vector3d to_faces = Eigen::Vector3d(1.0, 0.5, 0.25) - p.cwiseAbs();
    EXPECT_NEAR(d, -to_faces.minCoeff(), 1e-15);
  }
}

TEST(Shape, CylinderDistanceToItsSideItsEndsAndTheirRims) {
  const dc::Shape rod = cylinder(0.5, 2.0);  // along z from -1 to 1
  Eigen::Vector3d surface, normal;
  // Beside the curved side.
  EXPECT_NEAR(dc::signedDistance(rod, {0.0, 2.0, 0.3}, &surface, &normal), 1.5, 1e-15);
  EXPECT_NEAR((normal - Eigen::Vector3d(0, 1, 0)).norm(), 0.0, 1e-15);
  // Above an end.
  EXPECT_NEAR(dc::signedDistance(rod, {0.1, 0.2, -1.75}, &surface, &normal), 0.75, 1e-15);
  EXPECT_NEAR((normal - Eigen::Vector3d(0, 0, -1)).norm(), 0.0, 1e-15);
  // Beyond the rim: the distance to the circle.
  EXPECT_NEAR(dc::signedDistance(rod, {0.0, 0.8, 1.4}, &surface, &normal), 0.5, 1e-15);
  EXPECT_NEAR((surface - Eigen::Vector3d(0.0, 0.5, 1.0)).norm(), 0.0, 1e-15);
  // Inside: to the side or to an end, whichever is nearer.
  EXPECT_NEAR(dc::signedDistance(rod, {0.3, 0.0, 0.0}, &surface, &normal), -0.2, 1e-15);
  EXPECT_NEAR((normal - Eigen::Vector3d(1, 0, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(dc::signedDistance(rod, {0.0, 0.1, 0.9}, &surface, &normal), -0.1, 1e-15);
  EXPECT_NEAR((normal - Eigen::Vector3d(0, 0, 1)).norm(), 0.0, 1e-15);
  // On the axis, deep inside: a radius from the side.
  EXPECT_NEAR(dc::signedDistance(rod, {0.0, 0.0, 0.2}, &surface, &normal), -0.5, 1e-15);
  EXPECT_NEAR(normal.norm(), 1.0, 1e-15);
  EXPECT_NEAR(normal.z(), 0.0, 1e-15);
  expectConsistent(rod, 1.5, 3);
}

TEST(Shape, DistancesMoveWithTheShapesSize) {
  // Scaling a shape and the point by s scales the signed distance by s.
  const double s = 3.5;
  const Eigen::Vector3d p(0.4, -0.7, 0.9);
  EXPECT_NEAR(dc::signedDistance(box({1.0, 0.6, 0.8}), p) * s,
              dc::signedDistance(box(s * Eigen::Vector3d(1.0, 0.6, 0.8)), s * p), 1e-14);
  EXPECT_NEAR(dc::signedDistance(sphere(0.3), p) * s, dc::signedDistance(sphere(s * 0.3), s * p),
              1e-14);
  EXPECT_NEAR(dc::signedDistance(cylinder(0.3, 1.0), p) * s,
              dc::signedDistance(cylinder(s * 0.3, s * 1.0), s * p), 1e-14);
}

TEST(Shape, ValidationNamesTheShapeAndWhatItNeeds) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  auto refusal = [](const dc::Shape& shape) {
    return dt::thrownMessage<std::invalid_argument>([&] { dc::validate(shape, "obstacles[2]"); },
                                                    "accepted");
  };
  EXPECT_NO_THROW(dc::validate(box({1.0, 2.0, 3.0}), "b"));
  EXPECT_NO_THROW(dc::validate(sphere(0.1), "s"));
  EXPECT_NO_THROW(dc::validate(cylinder(0.1, 0.2), "c"));
  for (const Eigen::Vector3d& size :
       {Eigen::Vector3d(0.0, 1.0, 1.0), Eigen::Vector3d(1.0, -1.0, 1.0),
        Eigen::Vector3d(1.0, 1.0, nan), Eigen::Vector3d(inf, 1, 1)}) {
    EXPECT_EQ(refusal(box(size)), "obstacles[2]: a box needs three finite sizes > 0 m")
        << size.transpose();
  }
  for (double radius : {0.0, -0.1, nan, inf}) {
    EXPECT_EQ(refusal(sphere(radius)), "obstacles[2]: a sphere needs a finite radius > 0 m")
        << radius;
    EXPECT_EQ(refusal(cylinder(radius, 1.0)),
              "obstacles[2]: a cylinder needs a finite radius and length > 0 m")
        << radius;
    EXPECT_EQ(refusal(cylinder(1.0, radius)),
              "obstacles[2]: a cylinder needs a finite radius and length > 0 m")
        << radius;
  }
  dc::Shape mesh;
  mesh.kind = dc::Shape::Kind::kMesh;
  EXPECT_EQ(refusal(mesh), "obstacles[2]: a mesh shape needs its triangles");
}

TEST(Shape, PlacedShapesAreEqualOnlyWhenEverythingIs) {
  dc::PlacedShape a;
  a.name = "table";
  a.shape = box({1.0, 2.0, 0.1});
  a.pose.translation() = Eigen::Vector3d(0.0, 0.0, 0.7);
  dc::PlacedShape b = a;
  EXPECT_TRUE(a == b);
  b.name = "shelf";
  EXPECT_FALSE(a == b);
  b = a;
  b.pose.translation().z() += 1e-12;
  EXPECT_FALSE(a == b);
  b = a;
  b.shape.size.x() = std::nextafter(1.0, 2.0);
  EXPECT_FALSE(a == b);
  b = a;
  b.shape.kind = dc::Shape::Kind::kSphere;
  EXPECT_FALSE(a == b);
}
