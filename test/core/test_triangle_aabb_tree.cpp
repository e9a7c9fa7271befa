// The bounding-box tree over triangles: nearest points against the analytic distance to a box and
// against the triangle it names, and the triangles near a box: every one whose box meets it, each
// once, appended to what the caller holds.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <vector>

#include "deformable_sim/core/geometry/triangle_aabb_tree.h"
#include "deformable_sim/core/geometry/triangle_closest_point.h"
#include "deformable_sim/core/geometry/triangle_mesh.h"
#include "surface_test_helpers.h"
#include "thrown_message.h"

namespace dc = deformable_sim::core;
namespace dt = deformable_sim::test;

namespace {

// Whether triangle t's own bounding box meets the box [min, max].
bool boxMeets(const dc::TriangleMesh& mesh, int t, const Eigen::Vector3d& min,
              const Eigen::Vector3d& max) {
  Eigen::Vector3d low = mesh.vertices[mesh.triangles[t][0]], high = low;
  for (int c = 1; c < 3; ++c) {
    low = low.cwiseMin(mesh.vertices[mesh.triangles[t][c]]);
    high = high.cwiseMax(mesh.vertices[mesh.triangles[t][c]]);
  }
  return (low.array() <= max.array()).all() && (min.array() <= high.array()).all();
}

}  // namespace

TEST(TriangleAabbTree, ATreeOfNoTrianglesIsRefused) {
  const dc::TriangleMesh nothing;
  EXPECT_EQ(dt::thrownMessage<std::invalid_argument>([&] { dc::TriangleAabbTree tree(nothing); },
                                                     "accepted"),
            "a triangle tree needs at least one triangle");
  // An empty tree (before a built one is assigned) finds nothing near anything.
  const dc::TriangleAabbTree empty;
  std::vector<int> found;
  empty.trianglesNear(Eigen::Vector3d::Constant(-1e9), Eigen::Vector3d::Constant(1e9), found);
  EXPECT_TRUE(found.empty());
}

TEST(TriangleAabbTree, NearestPointOfABoxSurfaceIsAtTheBoxsDistance) {
  // Outside a box the distance to its surface is |max(|p - c| - h, 0)|.
  const Eigen::Vector3d min(-0.3, 0.1, -2.0), max(0.5, 0.4, 1.0);
  const Eigen::Vector3d centre = 0.5 * (min + max), half = 0.5 * (max - min);
  const dc::TriangleMesh box = dc::boxSurface(min, max);
  const dc::TriangleAabbTree tree(box);
  std::mt19937 random(17);
  std::uniform_real_distribution<double> coordinate(-4.0, 4.0);
  int checked = 0;
  while (checked < 300) {
    const Eigen::Vector3d p(coordinate(random), coordinate(random), coordinate(random));
    const Eigen::Vector3d excess = ((p - centre).cwiseAbs() - half).cwiseMax(0.0);
    if (excess.isZero(0.0)) continue;  // inside
    ++checked;
    const dc::TriangleAabbTree::Nearest nearest = tree.nearest(box, p);
    EXPECT_NEAR(std::sqrt(nearest.squared_distance), excess.norm(), 1e-12) << p.transpose();
    EXPECT_NEAR((p - nearest.closest.point).squaredNorm(), nearest.squared_distance, 1e-12);
  }
  // Inside, the nearest face: here the one at x = max.x.
  const dc::TriangleAabbTree::Nearest inside = tree.nearest(box, {0.45, 0.25, 0.0});
  EXPECT_NEAR(inside.squared_distance, 0.05 * 0.05, 1e-15);
  EXPECT_NEAR((inside.closest.point - Eigen::Vector3d(0.5, 0.25, 0.0)).norm(), 0.0, 1e-15);
}

TEST(TriangleAabbTree, TheNearestNamesItsTriangleAndItsVerticesAreAtZero) {
  const dc::TriangleMesh sphere = dt::sphereSurface(0.4, Eigen::Vector3d(1.0, -1.0, 0.5), 20, 40);
  const dc::TriangleAabbTree tree(sphere);
  std::mt19937 random(2);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  for (int k = 0; k < 100; ++k) {
    const Eigen::Vector3d p =
        Eigen::Vector3d(1.0, -1.0, 0.5) +
        Eigen::Vector3d(coordinate(random), coordinate(random), coordinate(random));
    const dc::TriangleAabbTree::Nearest nearest = tree.nearest(sphere, p);
    ASSERT_GE(nearest.triangle, 0);
    ASSERT_LT(nearest.triangle, static_cast<int>(sphere.triangles.size()));
    const Eigen::Vector3i& t = sphere.triangles[nearest.triangle];
    const dc::TriangleClosestPoint own = dc::closestPointOnTriangle(
        p, sphere.vertices[t[0]], sphere.vertices[t[1]], sphere.vertices[t[2]]);
    EXPECT_EQ(own.point, nearest.closest.point);
    EXPECT_EQ((p - own.point).squaredNorm(), nearest.squared_distance);
  }
  for (size_t v = 0; v < sphere.vertices.size(); v += 37) {
    EXPECT_EQ(tree.nearest(sphere, sphere.vertices[v]).squared_distance, 0.0) << v;
  }
}

TEST(TriangleAabbTree, TrianglesNearABoxAreEveryOneWhoseBoxMeetsItEachOnce) {
  const dc::TriangleMesh torus = dt::torusSurface(0.5, 0.15, 64, 24);
  const dc::TriangleAabbTree tree(torus);
  const int n = static_cast<int>(torus.triangles.size());
  std::mt19937 random(9);
  std::uniform_real_distribution<double> coordinate(-0.8, 0.8), extent(0.0, 0.3);
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d min(coordinate(random), coordinate(random), coordinate(random));
    const Eigen::Vector3d max =
        min + Eigen::Vector3d(extent(random), extent(random), extent(random));
    std::vector<int> found;
    tree.trianglesNear(min, max, found);
    const std::set<int> unique(found.begin(), found.end());
    EXPECT_EQ(unique.size(), found.size()) << "a triangle found twice";
    for (int t : found) {
      ASSERT_GE(t, 0);
      ASSERT_LT(t, n);
    }
    for (int t = 0; t < n; ++t) {
      if (boxMeets(torus, t, min, max)) {
        EXPECT_EQ(unique.count(t), 1u) << "missed " << t;
      }
    }
  }
}

TEST(TriangleAabbTree, AFarBoxFindsNothingAndAnAllEmbracingOneFindsAll) {
  const dc::TriangleMesh torus = dt::torusSurface(0.5, 0.15, 32, 12);
  const dc::TriangleAabbTree tree(torus);
  std::vector<int> found;
  tree.trianglesNear({2.0, 2.0, 2.0}, {3.0, 3.0, 3.0}, found);
  EXPECT_TRUE(found.empty());
  // Just above the torus's top (z = 0.15): nothing.
  tree.trianglesNear({-1.0, -1.0, 0.1501}, {1.0, 1.0, 1.0}, found);
  EXPECT_TRUE(found.empty());
  tree.trianglesNear({-1.0, -1.0, -1.0}, {1.0, 1.0, 1.0}, found);
  std::sort(found.begin(), found.end());
  std::vector<int> all(torus.triangles.size());
  for (size_t t = 0; t < all.size(); ++t) all[t] = static_cast<int>(t);
  EXPECT_EQ(found, all);
}

TEST(TriangleAabbTree, TrianglesNearAreAppendedToWhatTheCallerHolds) {
  const dc::TriangleMesh box = dc::boxSurface({0, 0, 0}, {1, 1, 1});
  const dc::TriangleAabbTree tree(box);
  std::vector<int> found = {-7, -8};
  // A small box at the corner (1, 1, 1), vertex 7: the six triangles of the three faces there.
  tree.trianglesNear({0.99, 0.99, 0.99}, {1.01, 1.01, 1.01}, found);
  ASSERT_GE(found.size(), 2u + 6u);
  EXPECT_EQ(found[0], -7);
  EXPECT_EQ(found[1], -8);
  for (size_t k = 2; k < found.size(); ++k) EXPECT_TRUE(found[k] >= 0 && found[k] < 12);
  for (int t = 0; t < 12; ++t) {
    const Eigen::Vector3i& c = box.triangles[t];
    if (c[0] == 7 || c[1] == 7 || c[2] == 7) {
      EXPECT_EQ(std::count(found.begin() + 2, found.end(), t), 1) << t;
    }
  }
}
