// How triangles join through their edges: open and overused edges, shells and whether each is
// closed, and the triangles facing against their neighbours, on surfaces whose answers can be
// counted by hand.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <numeric>
#include <vector>

#include "awkward_surfaces.h"
#include "deformable_sim/core/geometry/surface_topology.h"
#include "deformable_sim/core/geometry/triangle_mesh.h"
#include "surface_test_helpers.h"

namespace dc = deformable_sim::core;
namespace dt = deformable_sim::test;

namespace {

// Whether every entry of `topology` that reports a problem is clear.
void expectClean(const dc::SurfaceTopology& topology) {
  EXPECT_EQ(topology.open_edges, 0);
  EXPECT_EQ(topology.overused_edges, 0);
  EXPECT_EQ(topology.misoriented, 0);
  EXPECT_EQ(std::count(topology.against_neighbours.begin(), topology.against_neighbours.end(), 1),
            0);
  for (char closed : topology.shell_closed) EXPECT_EQ(closed, 1);
}

// The triangles t marks against their neighbours.
std::vector<int> marked(const dc::SurfaceTopology& topology) {
  std::vector<int> found;
  for (int t = 0; t < static_cast<int>(topology.against_neighbours.size()); ++t) {
    if (topology.against_neighbours[t]) found.push_back(t);
  }
  return found;
}

}  // namespace

TEST(SurfaceTopology, ABoxIsOneClosedShellFacingOneWay) {
  const dc::SurfaceTopology topology = dc::surfaceTopology(dc::boxSurface({0, 0, 0}, {1, 2, 3}));
  expectClean(topology);
  EXPECT_EQ(topology.shells, 1);
  EXPECT_EQ(topology.shell_of, std::vector<int>(12, 0));
  ASSERT_EQ(topology.shell_closed.size(), 1u);
  ASSERT_EQ(topology.against_neighbours.size(), 12u);
  // Facing inwards throughout is still facing one way.
  expectClean(dc::surfaceTopology(dt::turnedInsideOut(dc::boxSurface({0, 0, 0}, {1, 2, 3}))));
}

TEST(SurfaceTopology, AClosedTorusHasNoRimEither) {
  // Genus one: every edge still between exactly two triangles.
  const dc::TriangleMesh torus = dt::torusSurface(0.5, 0.2, 24, 12);
  const dc::SurfaceTopology topology = dc::surfaceTopology(torus);
  expectClean(topology);
  EXPECT_EQ(topology.shells, 1);
}

TEST(SurfaceTopology, ARemovedTriangleLeavesAHoleOfThreeOpenEdges) {
  dc::TriangleMesh box = dc::boxSurface({0, 0, 0}, {1, 1, 1});
  box.triangles.erase(box.triangles.begin() + 5);
  const dc::SurfaceTopology topology = dc::surfaceTopology(box);
  EXPECT_EQ(topology.open_edges, 3);
  EXPECT_EQ(topology.overused_edges, 0);
  EXPECT_EQ(topology.shells, 1);
  EXPECT_EQ(topology.shell_closed, std::vector<char>{0});
  EXPECT_EQ(topology.misoriented, 0);
}

TEST(SurfaceTopology, SeparateSurfacesAreSeparateShells) {
  // Two boxes, the second with a face missing, and a lone triangle.
  dc::TriangleMesh second = dc::boxSurface({2, 0, 0}, {3, 1, 1});
  second.triangles.resize(10);  // the last face (x = max) gone
  dc::TriangleMesh lone;
  lone.vertices = {{5, 0, 0}, {6, 0, 0}, {5, 1, 0}};
  lone.triangles = {{0, 1, 2}};
  const dc::TriangleMesh all =
      dt::joined(dt::joined(dc::boxSurface({0, 0, 0}, {1, 1, 1}), second), lone);
  const dc::SurfaceTopology topology = dc::surfaceTopology(all);
  EXPECT_EQ(topology.shells, 3);
  ASSERT_EQ(topology.shell_of.size(), 23u);
  // Shells are numbered in the order of their first triangle.
  for (int t = 0; t < 12; ++t) EXPECT_EQ(topology.shell_of[t], 0) << t;
  for (int t = 12; t < 22; ++t) EXPECT_EQ(topology.shell_of[t], 1) << t;
  EXPECT_EQ(topology.shell_of[22], 2);
  EXPECT_EQ(topology.shell_closed, (std::vector<char>{1, 0, 0}));
  EXPECT_EQ(topology.open_edges, 4 + 3);  // the missing face's rim and the lone triangle's sides
  EXPECT_EQ(topology.misoriented, 0);
}

TEST(SurfaceTopology, CoincidentButDistinctVerticesDoNotJoin) {
  // A triangle soup (each triangle its own three vertices, as STL stores them): in the same
  // places as a closed box, and yet nothing shares an edge.
  const dc::TriangleMesh box = dc::boxSurface({0, 0, 0}, {1, 1, 1});
  dc::TriangleMesh soup;
  for (const Eigen::Vector3i& t : box.triangles) {
    const int first = static_cast<int>(soup.vertices.size());
    for (int c = 0; c < 3; ++c) soup.vertices.push_back(box.vertices[t[c]]);
    soup.triangles.emplace_back(first, first + 1, first + 2);
  }
  const dc::SurfaceTopology topology = dc::surfaceTopology(soup);
  EXPECT_EQ(topology.shells, 12);
  EXPECT_EQ(topology.open_edges, 36);
  EXPECT_EQ(topology.misoriented, 0);
  EXPECT_EQ(std::count(topology.shell_closed.begin(), topology.shell_closed.end(), 0), 12);
}

TEST(SurfaceTopology, AFinOnAnEdgeOverusesIt) {
  // Three triangles on the edge (0, 1): a fin, as where two solids touch along a line.
  dc::TriangleMesh fin;
  fin.vertices = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}, {0.5, 0, 1}};
  fin.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  const dc::SurfaceTopology topology = dc::surfaceTopology(fin);
  EXPECT_EQ(topology.overused_edges, 1);
  EXPECT_EQ(topology.open_edges, 6);
  EXPECT_EQ(topology.shells, 1);
  EXPECT_EQ(topology.shell_closed, std::vector<char>{0});
}

TEST(SurfaceTopology, ATurnedTriangleIsTheOneMarked) {
  for (int turned : {0, 5, 11}) {
    dc::TriangleMesh box = dc::boxSurface({0, 0, 0}, {1, 1, 1});
    std::swap(box.triangles[turned][1], box.triangles[turned][2]);
    const dc::SurfaceTopology topology = dc::surfaceTopology(box);
    EXPECT_EQ(topology.misoriented, 1) << turned;
    EXPECT_EQ(marked(topology), std::vector<int>{turned});
    // Its edges are still each between two triangles: the shell is closed as a set of edges.
    EXPECT_EQ(topology.open_edges, 0);
    EXPECT_EQ(topology.shell_closed, std::vector<char>{1});
  }
}

TEST(SurfaceTopology, TheSmallerGroupIsMarkedWhicheverFacesOutwards) {
  // Two whole faces (four triangles) of a box turned: those four are the minority, marked, even
  // when the first triangle is among them.
  for (int first_face : {0, 3}) {
    dc::TriangleMesh box = dc::boxSurface({0, 0, 0}, {1, 1, 1});
    std::vector<int> turned = {2 * first_face, 2 * first_face + 1, 2 * first_face + 4,
                               2 * first_face + 5};
    for (int t : turned) std::swap(box.triangles[t][1], box.triangles[t][2]);
    const dc::SurfaceTopology topology = dc::surfaceTopology(box);
    EXPECT_EQ(topology.misoriented, 4) << first_face;
    EXPECT_EQ(marked(topology), turned) << first_face;
  }
  // Turn the other eight instead: the same four are the minority.
  dc::TriangleMesh box = dc::boxSurface({0, 0, 0}, {1, 1, 1});
  std::vector<int> kept = {0, 1, 4, 5};
  for (int t = 0; t < 12; ++t) {
    if (std::find(kept.begin(), kept.end(), t) == kept.end()) {
      std::swap(box.triangles[t][1], box.triangles[t][2]);
    }
  }
  EXPECT_EQ(marked(dc::surfaceTopology(box)), kept);
}

TEST(SurfaceTopology, NothingHasNoShells) {
  const dc::SurfaceTopology topology = dc::surfaceTopology(dc::TriangleMesh{});
  EXPECT_EQ(topology.shells, 0);
  EXPECT_EQ(topology.open_edges, 0);
  EXPECT_TRUE(topology.shell_of.empty());
  EXPECT_TRUE(topology.shell_closed.empty());
  EXPECT_TRUE(topology.against_neighbours.empty());
}
