// Whether a surface is closed, and the caps that close it: each open edge answered by a triangle
// the other way round to its hole's apex, the apex at the mean of the hole's rim, and the surface
// with its caps closed, enclosing what its rim bounds.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <map>
#include <utility>
#include <vector>

#include "awkward_surfaces.h"
#include "deformable_sim/core/geometry/hole_caps.h"
#include "deformable_sim/core/geometry/triangle_mesh.h"
#include "surface_meters.h"
#include "surface_test_helpers.h"

namespace dc = deformable_sim::core;
namespace dt = deformable_sim::test;

namespace {

// `surface` without the triangles for which `drop` is true.
template <typename Drop>
dc::TriangleMesh without(dc::TriangleMesh surface, Drop drop) {
  surface.triangles.erase(
      std::remove_if(surface.triangles.begin(), surface.triangles.end(),
                     [&](const Eigen::Vector3i& t) { return drop(surface, t); }),
      surface.triangles.end());
  return surface;
}

// Whether every corner of t has coordinate `axis` equal to `value`.
bool onPlane(const dc::TriangleMesh& s, const Eigen::Vector3i& t, int axis, double value) {
  for (int c = 0; c < 3; ++c) {
    if (s.vertices[t[c]][axis] != value) return false;
  }
  return true;
}

// The surface's triangles and its caps' as one surface (the caps' vertices are the surface's,
// then the apexes).
dc::TriangleMesh capped(const dc::TriangleMesh& surface, const dc::TriangleMesh& caps) {
  dc::TriangleMesh closed = caps;
  closed.triangles.insert(closed.triangles.begin(), surface.triangles.begin(),
                          surface.triangles.end());
  return closed;
}

}  // namespace

TEST(HoleCaps, ClosedSurfacesAreRecognized) {
  EXPECT_TRUE(dc::isClosedSurface(dc::boxSurface({0, 0, 0}, {1, 2, 3})));
  EXPECT_TRUE(dc::isClosedSurface(dt::torusSurface(0.1, 0.03, 16, 8)));
  EXPECT_TRUE(dc::isClosedSurface(dt::sphericalShell(0.2, 0.1, Eigen::Vector3d::Zero(), 8, 12)));
  // A triangle and the same triangle turned: their edges cancel.
  dc::TriangleMesh sheet;
  sheet.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  sheet.triangles = {{0, 1, 2}, {0, 2, 1}};
  EXPECT_TRUE(dc::isClosedSurface(sheet));
  EXPECT_TRUE(dc::isClosedSurface(dc::TriangleMesh{}));  // nothing open in nothing
}

TEST(HoleCaps, OpenAndInconsistentlyTurnedSurfacesAreNot) {
  dc::TriangleMesh box = dc::boxSurface({0, 0, 0}, {1, 2, 3});
  dc::TriangleMesh open = box;
  open.triangles.pop_back();
  EXPECT_FALSE(dc::isClosedSurface(open));
  // Every edge has two triangles, but one of them is turned: its edges run twice one way.
  std::swap(box.triangles[4][1], box.triangles[4][2]);
  EXPECT_FALSE(dc::isClosedSurface(box));
}

TEST(HoleCaps, AClosedSurfaceNeedsNoCap) {
  const dc::TriangleMesh torus = dt::torusSurface(0.1, 0.03, 16, 8);
  const dc::TriangleMesh caps = dc::holeCaps(torus);
  EXPECT_TRUE(caps.triangles.empty());
  EXPECT_EQ(caps.vertices, torus.vertices);
}

TEST(HoleCaps, AnOpenBoxIsClosedByAFanOverItsMissingFace) {
  const Eigen::Vector3d min(-0.2, 0.1, 0.0), max(0.4, 0.3, 0.5);
  const dc::TriangleMesh open =
      without(dc::boxSurface(min, max), [&](const auto& s, const auto& t) {
        return onPlane(s, t, 2, max.z());  // the top
      });
  ASSERT_EQ(open.triangles.size(), 10u);
  ASSERT_FALSE(dc::isClosedSurface(open));
  const dc::TriangleMesh caps = dc::holeCaps(open);
  // One apex, at the mean of the rim's four corners: the centre of the missing face.
  ASSERT_EQ(caps.vertices.size(), 9u);
  EXPECT_EQ(std::vector<Eigen::Vector3d>(caps.vertices.begin(), caps.vertices.begin() + 8),
            open.vertices);
  const Eigen::Vector3d apex(0.5 * (min.x() + max.x()), 0.5 * (min.y() + max.y()), max.z());
  EXPECT_NEAR((caps.vertices[8] - apex).norm(), 0.0, 1e-15);
  // A triangle per rim edge (the missing face's diagonal was shared: not open), each to the apex
  // and facing out of the box, covering the face.
  ASSERT_EQ(caps.triangles.size(), 4u);
  for (int t = 0; t < 4; ++t) {
    EXPECT_EQ(caps.triangles[t][2], 8);
    EXPECT_GT(dt::areaVector(caps, t).z(), 0.0) << t;
  }
  EXPECT_NEAR(dt::surfaceArea(caps), (max - min).head<2>().prod(), 1e-15);
  const dc::TriangleMesh closed = capped(open, caps);
  EXPECT_TRUE(dc::isClosedSurface(closed));
  EXPECT_NEAR(dt::divergenceVolume(closed), (max - min).prod(), 1e-15);
}

TEST(HoleCaps, EachCapAnswersItsOpenEdgeTurnedRound) {
  // A box without two opposite faces: two holes, an apex each, and every open edge (a, b) of the
  // surface met by the cap (b, a, apex) of its own hole.
  const Eigen::Vector3d min(0, 0, 0), max(1, 2, 3);
  const dc::TriangleMesh tube =
      without(dc::boxSurface(min, max), [&](const auto& s, const auto& t) {
        return onPlane(s, t, 0, min.x()) || onPlane(s, t, 0, max.x());
      });
  const dc::TriangleMesh caps = dc::holeCaps(tube);
  ASSERT_EQ(caps.vertices.size(), 10u);
  ASSERT_EQ(caps.triangles.size(), 8u);
  std::map<std::pair<int, int>, int> apex_of_edge;
  for (const Eigen::Vector3i& t : caps.triangles) apex_of_edge[{t[1], t[0]}] = t[2];
  for (const auto& [edge, count] : dt::directedEdges(tube)) {
    if (dt::directedEdges(tube).count({edge.second, edge.first})) continue;  // not open
    ASSERT_EQ(apex_of_edge.count(edge), 1u) << edge.first << " " << edge.second;
    // Its apex is on the same face of the box as the edge.
    const double x = tube.vertices[edge.first].x();
    EXPECT_EQ(tube.vertices[edge.second].x(), x);
    EXPECT_NEAR(caps.vertices[apex_of_edge[edge]].x(), x, 1e-15);
  }
  EXPECT_NE(caps.vertices[8].x(), caps.vertices[9].x());  // two apexes, one per end
  const dc::TriangleMesh closed = capped(tube, caps);
  EXPECT_TRUE(dc::isClosedSurface(closed));
  EXPECT_NEAR(dt::divergenceVolume(closed), 6.0, 1e-14);
}

TEST(HoleCaps, AnEdgeOpenTwiceGetsTwoCaps) {
  // The same triangle twice, facing the same way: each edge used twice more one way.
  dc::TriangleMesh doubled;
  doubled.vertices = {{0, 0, 0}, {3, 0, 0}, {0, 3, 0}};
  doubled.triangles = {{0, 1, 2}, {0, 1, 2}};
  const dc::TriangleMesh caps = dc::holeCaps(doubled);
  ASSERT_EQ(caps.vertices.size(), 4u);
  EXPECT_NEAR((caps.vertices[3] - Eigen::Vector3d(1, 1, 0)).norm(), 0.0, 1e-15);  // centroid
  EXPECT_EQ(caps.triangles.size(), 6u);
  const dc::TriangleMesh closed = capped(doubled, caps);
  EXPECT_TRUE(dc::isClosedSurface(closed));
  EXPECT_NEAR(dt::divergenceVolume(closed), 0.0, 1e-15);  // flat: encloses nothing
}

TEST(HoleCaps, ACurvedRimIsClosedAndTheCapsTakeTheVolumeUnderTheirFan) {
  // A UV sphere with the band of triangles around the north pole removed: its rim is a ring of
  // latitude, and the fan to the ring's centre is a flat disc. The closed surface holds the
  // sphere polygon's volume less the cone of the pole over that disc.
  const int rings = 10, segments = 24;
  const dc::TriangleMesh sphere = dt::sphereSurface(1.0, Eigen::Vector3d::Zero(), rings, segments);
  const int north = static_cast<int>(sphere.vertices.size()) - 1;
  const dc::TriangleMesh open = without(sphere, [&](const auto&, const Eigen::Vector3i& t) {
    return t[0] == north || t[1] == north || t[2] == north;
  });
  ASSERT_EQ(open.triangles.size(), sphere.triangles.size() - segments);
  const dc::TriangleMesh caps = dc::holeCaps(open);
  ASSERT_EQ(caps.triangles.size(), static_cast<size_t>(segments));
  const Eigen::Vector3d apex = caps.vertices.back();
  const double polar = M_PI / rings;  // of the last ring, from +z
  EXPECT_NEAR((apex - Eigen::Vector3d(0, 0, std::cos(polar))).norm(), 0.0, 1e-14);
  const dc::TriangleMesh closed = capped(open, caps);
  EXPECT_TRUE(dc::isClosedSurface(closed));
  // The removed fan and the cap share the ring: the difference is a pyramid of height
  // 1 - cos(polar) over the regular polygon of `segments` sides and circumradius sin(polar).
  const double ring_area =
      0.5 * segments * std::pow(std::sin(polar), 2) * std::sin(2 * M_PI / segments);
  const double pyramid = ring_area * (1.0 - std::cos(polar)) / 3.0;
  EXPECT_NEAR(dt::divergenceVolume(closed), dt::divergenceVolume(sphere) - pyramid, 1e-13);
}
