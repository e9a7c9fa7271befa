// The generalized winding number: solid angles against their closed forms, integer values inside
// and outside closed surfaces, the fraction a hole leaves, invariance under moving and scaling,
// and the tree's far-field sums against the exact sum.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

#include "awkward_surfaces.h"
#include "deformable_sim/core/geometry/triangle_mesh.h"
#include "deformable_sim/core/geometry/winding_number.h"
#include "surface_meters.h"
#include "surface_test_helpers.h"

namespace dc = deformable_sim::core;
namespace dt = deformable_sim::test;

namespace {

const Eigen::Vector3d kX = Eigen::Vector3d::UnitX(), kY = Eigen::Vector3d::UnitY(),
                      kZ = Eigen::Vector3d::UnitZ();

// The unit cube [-1, 1]^3 minus its top face (z = 1).
dc::TriangleMesh cubeWithoutTop() {
  dc::TriangleMesh cube = dc::boxSurface(-Eigen::Vector3d::Ones(), Eigen::Vector3d::Ones());
  std::vector<Eigen::Vector3i> kept;
  for (const Eigen::Vector3i& t : cube.triangles) {
    if (cube.vertices[t[0]].z() + cube.vertices[t[1]].z() + cube.vertices[t[2]].z() < 3.0) {
      kept.push_back(t);
    }
  }
  cube.triangles = kept;
  return cube;
}

// The solid angle of an a x b rectangle seen from distance d on the normal through its centre.
double rectangleSolidAngle(double a, double b, double d) {
  return 4.0 * std::asin(a * b / std::sqrt((a * a + 4 * d * d) * (b * b + 4 * d * d)));
}

}  // namespace

TEST(SolidAngle, AnOctantIsAnEighthOfTheSphere) {
  // The triangle of the three unit axes, seen from the origin behind it (its normal (1, 1, 1)
  // points away): counter-clockwise, +4 pi / 8.
  EXPECT_NEAR(dc::solidAngle(kX, kY, kZ, Eigen::Vector3d::Zero()), M_PI / 2.0, 1e-15);
  EXPECT_NEAR(dc::solidAngle(kX, kZ, kY, Eigen::Vector3d::Zero()), -M_PI / 2.0, 1e-15);
  // The same corners in cyclic order are the same triangle.
  EXPECT_NEAR(dc::solidAngle(kY, kZ, kX, Eigen::Vector3d::Zero()), M_PI / 2.0, 1e-15);
  // Scaled about q and moved with q: unchanged.
  const Eigen::Vector3d q(0.3, -2.0, 5.0);
  EXPECT_NEAR(dc::solidAngle(q + 7.0 * kX, q + 7.0 * kY, q + 7.0 * kZ, q), M_PI / 2.0, 1e-14);
}

TEST(SolidAngle, ACubeFaceSeenFromTheCentreIsASixthOfTheSphere) {
  // The face z = 1 of [-1, 1]^3 as its two triangles, from the centre: 4 pi / 6 together, and by
  // the face's symmetry 4 pi / 12 each. From a corner of the cube, the three faces away from it
  // fill its octant, 4 pi / 8, one third each.
  const Eigen::Vector3d a(-1, -1, 1), b(1, -1, 1), c(1, 1, 1), d(-1, 1, 1);
  const Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  EXPECT_NEAR(dc::solidAngle(a, b, c, centre), M_PI / 3.0, 1e-14);
  EXPECT_NEAR(dc::solidAngle(a, c, d, centre), M_PI / 3.0, 1e-14);
  EXPECT_NEAR(dc::solidAngle(a, b, c, centre) + dc::solidAngle(a, c, d, centre),
              rectangleSolidAngle(2.0, 2.0, 1.0), 1e-14);
  const Eigen::Vector3d corner(-1, -1, -1);
  EXPECT_NEAR(dc::solidAngle(a, b, c, corner) + dc::solidAngle(a, c, d, corner), M_PI / 6.0, 1e-14);
}

TEST(SolidAngle, ZeroInTheTrianglesPlaneAndADipoleFarAway) {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_NEAR(dc::solidAngle(a, b, c, Eigen::Vector3d(3.0, 2.0, 0.0)), 0.0, 1e-15);
  EXPECT_NEAR(dc::solidAngle(a, b, c, Eigen::Vector3d(-1.0, 0.5, 0.0)), 0.0, 1e-15);
  // Far away, the triangle (area 1/2, normal +z, centroid g) subtends A n . (g - q) / |g - q|^3,
  // to a relative error of the order of (size / distance)^2.
  const Eigen::Vector3d g(1.0 / 3.0, 1.0 / 3.0, 0.0);
  for (const Eigen::Vector3d& direction :
       {Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(0.3, -0.5, -1).normalized(),
        Eigen::Vector3d(1, 1, 0.5).normalized()}) {
    const Eigen::Vector3d q = g + 200.0 * direction;
    const Eigen::Vector3d r = g - q;
    const double dipole = 0.5 * kZ.dot(r) / std::pow(r.norm(), 3);
    EXPECT_NEAR(dc::solidAngle(a, b, c, q) / dipole, 1.0, 1e-4) << direction.transpose();
  }
}

TEST(WindingNumber, ClosedSurfacesCountHowOftenTheyWindAroundAPoint) {
  const dc::TriangleMesh box = dc::boxSurface({-1, -2, -3}, {1, 2, 3});
  for (const Eigen::Vector3d& inside :
       {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.99, -1.99, 2.99),
        Eigen::Vector3d(-0.5, 1, 0)}) {
    EXPECT_NEAR(dc::exactWindingNumber(box, inside), 1.0, 1e-13) << inside.transpose();
    EXPECT_NEAR(dc::exactWindingNumber(dt::turnedInsideOut(box), inside), -1.0, 1e-13);
  }
  for (const Eigen::Vector3d& outside :
       {Eigen::Vector3d(1.01, 0, 0), Eigen::Vector3d(5, 5, 5), Eigen::Vector3d(0, 0, -3.001)}) {
    EXPECT_NEAR(dc::exactWindingNumber(box, outside), 0.0, 1e-13) << outside.transpose();
  }
  // A box inside another: twice around the points in both.
  const dc::TriangleMesh nested =
      dt::joined(box, dc::boxSurface({-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}));
  EXPECT_NEAR(dc::exactWindingNumber(nested, Eigen::Vector3d(0.1, 0.2, 0.3)), 2.0, 1e-13);
  EXPECT_NEAR(dc::exactWindingNumber(nested, Eigen::Vector3d(0.1, 1.5, 0.3)), 1.0, 1e-13);
}

TEST(WindingNumber, AMissingFaceTakesItsSolidAngleAway) {
  // From the centre of a cube each face is a sixth of the sphere: without one, 5/6.
  const dc::TriangleMesh open = cubeWithoutTop();
  EXPECT_NEAR(dc::exactWindingNumber(open, Eigen::Vector3d::Zero()), 5.0 / 6.0, 1e-14);
  // Elsewhere on the axis, the closed cube's value less the missing face's share: behind it
  // (inside) that share counts positive, in front of it (outside) negative.
  const double below = 1.0 - rectangleSolidAngle(2.0, 2.0, 1.99) / (4.0 * M_PI);
  EXPECT_NEAR(dc::exactWindingNumber(open, Eigen::Vector3d(0, 0, -0.99)), below, 1e-13);
  const double above = rectangleSolidAngle(2.0, 2.0, 0.5) / (4.0 * M_PI);
  EXPECT_NEAR(dc::exactWindingNumber(open, Eigen::Vector3d(0, 0, 1.5)), above, 1e-13);
  // Across the missing face the value is continuous (no jump of 1 as through a face).
  EXPECT_NEAR(dc::exactWindingNumber(open, Eigen::Vector3d(0.1, 0.2, 1.0 - 1e-7)),
              dc::exactWindingNumber(open, Eigen::Vector3d(0.1, 0.2, 1.0 + 1e-7)), 1e-6);
  // The tree over so few triangles is one leaf: exact.
  const dc::WindingNumber winding(open);
  EXPECT_NEAR(winding.at(Eigen::Vector3d::Zero()), 5.0 / 6.0, 1e-14);
}

TEST(WindingNumber, MovingAndScalingSurfaceAndPointTogetherChangesNothing) {
  const dc::TriangleMesh open = cubeWithoutTop();
  const Eigen::Isometry3d pose = Eigen::Translation3d(4.0, -3.0, 0.5) *
                                 Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized());
  const double scale = 0.01;
  dc::TriangleMesh moved = open;
  for (Eigen::Vector3d& v : moved.vertices) v = pose * (scale * v);
  for (const Eigen::Vector3d& q : {Eigen::Vector3d(0.2, 0.1, 0.0), Eigen::Vector3d(0.3, -0.4, 1.3),
                                   Eigen::Vector3d(2, 0, 0)}) {
    EXPECT_NEAR(dc::exactWindingNumber(moved, pose * (scale * q)), dc::exactWindingNumber(open, q),
                1e-12)
        << q.transpose();
  }
}

TEST(WindingNumber, TheTreeOfAnEmptySurfaceGivesZero) {
  const dc::TriangleMesh empty;
  const dc::WindingNumber winding(empty);
  EXPECT_EQ(winding.at(Eigen::Vector3d(1, 2, 3)), 0.0);
  EXPECT_EQ(dc::exactWindingNumber(empty, Eigen::Vector3d(1, 2, 3)), 0.0);
}

TEST(WindingNumber, FarFromAClosedSurfaceTheTreeCancelsToZero) {
  // Seen from beyond kFarRatio times its radius, the whole surface is one dipole of area vector
  // sum(A n) = 0 for a closed surface.
  const dc::TriangleMesh torus = dt::torusSurface(1.0, 0.3, 48, 16);
  const dc::WindingNumber winding(torus);
  for (const Eigen::Vector3d& q : {Eigen::Vector3d(10, 0, 0), Eigen::Vector3d(-3, 7, 9)}) {
    EXPECT_NEAR(winding.at(q), 0.0, 1e-14) << q.transpose();
  }
}

namespace {

// The upper half of a UV sphere of radius 0.5 about (0.1, 0.2, 0.3): an open, curved sheet
// with fractional winding numbers everywhere.
dc::TriangleMesh hemisphere() {
  dc::TriangleMesh sphere = dt::sphereSurface(0.5, Eigen::Vector3d(0.1, 0.2, 0.3), 32, 64);
  std::vector<Eigen::Vector3i> upper;
  for (const Eigen::Vector3i& t : sphere.triangles) {
    if (sphere.vertices[t[0]].z() + sphere.vertices[t[1]].z() + sphere.vertices[t[2]].z() > 0.9) {
      upper.push_back(t);
    }
  }
  sphere.triangles = upper;
  return sphere;
}

// A point `distance` from the hemisphere's pole, below it.
Eigen::Vector3d farBelow(double distance) {
  return Eigen::Vector3d(0.1, 0.2, 0.8) + distance * Eigen::Vector3d(0.3, -0.2, -1.0).normalized();
}

}  // namespace

TEST(WindingNumber, TheTreeAgreesWithTheExactSumAroundAnOpenSurface) {
  const dc::TriangleMesh sheet = hemisphere();
  ASSERT_GT(sheet.triangles.size(), 1000u);
  const dc::WindingNumber winding(sheet);
  std::mt19937 random(3);
  std::uniform_real_distribution<double> coordinate(-1.5, 1.5);
  double largest_error = 0.0;
  for (int k = 0; k < 300; ++k) {
    const Eigen::Vector3d q(coordinate(random), coordinate(random), coordinate(random));
    largest_error =
        std::max(largest_error, std::abs(winding.at(q) - dc::exactWindingNumber(sheet, q)));
  }
  EXPECT_LT(largest_error, 0.02);  // far below the margin of a threshold at 1/2
}

TEST(WindingNumber, FarAwayTheTreeIsTheWholeSheetsDipole) {
  // Beyond kFarRatio times its radius the sheet is one group: sum(A n) . r / |r|^3 / 4 pi, with
  // r from its area-weighted centroid to the point.
  const dc::TriangleMesh sheet = hemisphere();
  const dc::WindingNumber winding(sheet);
  Eigen::Vector3d area_normal = Eigen::Vector3d::Zero(), centroid = Eigen::Vector3d::Zero();
  for (int t = 0; t < static_cast<int>(sheet.triangles.size()); ++t) {
    const Eigen::Vector3i& c = sheet.triangles[t];
    area_normal += dt::areaVector(sheet, t);
    centroid += dt::areaVector(sheet, t).norm() *
                (sheet.vertices[c[0]] + sheet.vertices[c[1]] + sheet.vertices[c[2]]) / 3.0;
  }
  centroid /= dt::surfaceArea(sheet);
  for (double distance : {5.0, 40.0}) {
    const Eigen::Vector3d r = centroid - farBelow(distance);
    const double dipole = area_normal.dot(r) / std::pow(r.norm(), 3) / (4.0 * M_PI);
    EXPECT_NEAR(winding.at(farBelow(distance)) / dipole, 1.0, 1e-10) << distance;
  }
}

TEST(WindingNumber, TheDipolesErrorFallsWithDistance) {
  // A curved group's dipole is off by a first-order term, n (y - c) summed over its area: the
  // error halves each time the distance doubles, and stays below radius / distance.
  const dc::TriangleMesh sheet = hemisphere();
  const dc::WindingNumber winding(sheet);
  double previous = 0.0;
  for (double distance : {10.0, 20.0, 40.0, 80.0}) {
    const double exact = dc::exactWindingNumber(sheet, farBelow(distance));
    const double error = std::abs(winding.at(farBelow(distance)) / exact - 1.0);
    EXPECT_LT(error, 0.5 / distance) << distance;
    if (previous > 0.0) {
      EXPECT_NEAR(error / previous, 0.5, 0.05) << distance;
    }
    previous = error;
  }
}
