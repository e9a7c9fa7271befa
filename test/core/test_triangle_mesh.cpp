// Triangle surfaces: the box surface (its corners, closed, facing out, the right volume and area)
// and the flat arrays a message carries (round trip, and what unflatten refuses).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "deformable_sim/core/geometry/triangle_mesh.h"
#include "surface_meters.h"
#include "thrown_message.h"

namespace dc = deformable_sim::core;
namespace dt = deformable_sim::test;

TEST(BoxSurface, CornersFollowTheBitsOfTheirIndex) {
  const Eigen::Vector3d min(-0.5, 0.1, 2.0), max(0.25, 0.4, 3.5);
  const dc::TriangleMesh box = dc::boxSurface(min, max);
  ASSERT_EQ(box.vertices.size(), 8u);
  for (int c = 0; c < 8; ++c) {
    EXPECT_EQ(box.vertices[c].x(), (c & 1) ? max.x() : min.x()) << c;
    EXPECT_EQ(box.vertices[c].y(), (c & 2) ? max.y() : min.y()) << c;
    EXPECT_EQ(box.vertices[c].z(), (c & 4) ? max.z() : min.z()) << c;
  }
}

TEST(BoxSurface, IsClosedWithEveryTriangleFacingOut) {
  const Eigen::Vector3d min(-0.5, 0.1, 2.0), max(0.25, 0.4, 3.5);
  const dc::TriangleMesh box = dc::boxSurface(min, max);
  ASSERT_EQ(box.triangles.size(), 12u);
  // Closed and consistently turned: each directed edge once, and its reverse once.
  for (const auto& [edge, count] : dt::directedEdges(box)) {
    EXPECT_EQ(count, 1) << edge.first << " " << edge.second;
    EXPECT_EQ(dt::directedEdges(box).count({edge.second, edge.first}), 1u);
  }
  // Each triangle lies in a face of the box, its normal along the outward axis of that face.
  const Eigen::Vector3d centre = 0.5 * (min + max);
  for (int t = 0; t < 12; ++t) {
    const Eigen::Vector3d normal = dt::areaVector(box, t).normalized();
    int axis = 0;
    EXPECT_NEAR(normal.cwiseAbs().maxCoeff(&axis), 1.0, 1e-15) << t;
    const Eigen::Vector3d corner = box.vertices[box.triangles[t][0]];
    EXPECT_GT(normal[axis] * (corner[axis] - centre[axis]), 0.0) << t;
  }
  const Eigen::Vector3d size = max - min;
  EXPECT_NEAR(dt::divergenceVolume(box), size.prod(), 1e-14);
  EXPECT_NEAR(dt::surfaceArea(box),
              2.0 * (size.x() * size.y() + size.y() * size.z() + size.z() * size.x()), 1e-14);
}

TEST(TriangleMeshArrays, FlattenThenUnflattenGivesTheSameMesh) {
  dc::TriangleMesh mesh = dc::boxSurface({-1.0, 0.0, 1e-9}, {M_PI, 1e5, 2.0});
  std::vector<double> vertices;
  std::vector<uint32_t> triangles;
  dc::flatten(mesh, vertices, triangles);
  ASSERT_EQ(vertices.size(), 3 * mesh.vertices.size());
  ASSERT_EQ(triangles.size(), 3 * mesh.triangles.size());
  EXPECT_EQ(vertices[3 * 7 + 1], mesh.vertices[7].y());
  EXPECT_EQ(triangles[3 * 5 + 2], static_cast<uint32_t>(mesh.triangles[5][2]));
  const dc::TriangleMesh back = dc::unflatten(vertices, triangles, "test");
  EXPECT_EQ(back.vertices, mesh.vertices);  // bit for bit
  EXPECT_EQ(back.triangles, mesh.triangles);
}

TEST(TriangleMeshArrays, FlattenAppendsToWhatTheArraysHold) {
  // Two meshes into one pair of arrays: the second's indices are its own (not offset).
  const dc::TriangleMesh a = dc::boxSurface({0, 0, 0}, {1, 1, 1});
  const dc::TriangleMesh b = dc::boxSurface({2, 0, 0}, {3, 1, 1});
  std::vector<double> vertices;
  std::vector<uint32_t> triangles;
  dc::flatten(a, vertices, triangles);
  dc::flatten(b, vertices, triangles);
  EXPECT_EQ(vertices.size(), 48u);
  EXPECT_EQ(triangles.size(), 72u);
  EXPECT_EQ(vertices[24], 2.0);  // b's first vertex after a's eight
  EXPECT_EQ(std::vector<uint32_t>(triangles.begin() + 36, triangles.end()),
            std::vector<uint32_t>(triangles.begin(), triangles.begin() + 36));
}

TEST(TriangleMeshArrays, EmptyArraysAreAnEmptyMesh) {
  const dc::TriangleMesh empty = dc::unflatten({}, {}, "test");
  EXPECT_TRUE(empty.vertices.empty());
  EXPECT_TRUE(empty.triangles.empty());
}

TEST(TriangleMeshArrays, UnflattenRefusesArraysThatDoNotFitNamingWhat) {
  const std::vector<double> two_vertices = {0, 0, 0, 1, 0, 0};
  auto refusal = [](const std::vector<double>& v, const std::vector<uint32_t>& t) {
    return dt::thrownMessage<std::invalid_argument>(
        [&] { dc::unflatten(v, t, "obstacle 'table'"); }, "accepted");
  };
  EXPECT_EQ(refusal({0, 0, 0, 1, 0}, {}),
            "obstacle 'table': its vertices and triangles must come in threes");
  EXPECT_EQ(refusal(two_vertices, {0, 1}),
            "obstacle 'table': its vertices and triangles must come in threes");
  // Index 2 is one past the last of two vertices; every corner is checked, the last too.
  EXPECT_EQ(refusal(two_vertices, {0, 1, 2}),
            "obstacle 'table': a triangle refers to vertex 2 of 2");
  EXPECT_EQ(refusal(two_vertices, {2, 0, 1}),
            "obstacle 'table': a triangle refers to vertex 2 of 2");
  EXPECT_EQ(refusal({}, {0, 0, 0}), "obstacle 'table': a triangle refers to vertex 0 of 0");
  EXPECT_EQ(refusal(two_vertices, {0, 1, 4294967295u}),
            "obstacle 'table': a triangle refers to vertex 4294967295 of 2");
}
