// The UV sphere the tests and the scan-blob benchmark make their balls and blobs of: its vertex
// order, its closed outward-facing surface, and the radius asked once per vertex.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "deformable_sim/core/geometry/uv_sphere.h"

namespace dc = deformable_sim::core;

namespace {

/// The volume the surface encloses, m^3: positive when its triangles face outwards.
double enclosedVolume(const dc::TriangleMesh& mesh) {
  double volume = 0.0;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    volume += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]])) / 6.0;
  }
  return volume;
}

}  // namespace

TEST(UvSphere, HasItsPolesAndRingsInOrder) {
  const int rings = 4, segments = 6;
  const dc::TriangleMesh mesh = dc::uvSphere(rings, segments, [](double, double) { return 2.0; });
  ASSERT_EQ(mesh.vertices.size(), 2u + (rings - 1) * segments);
  EXPECT_EQ(mesh.triangles.size(), 2u * segments * (rings - 1));
  EXPECT_LT((mesh.vertices.front() - Eigen::Vector3d(0, 0, -2)).norm(), 1e-15);  // south pole
  EXPECT_LT((mesh.vertices.back() - Eigen::Vector3d(0, 0, 2)).norm(), 1e-15);    // north pole
  for (const Eigen::Vector3d& v : mesh.vertices) EXPECT_NEAR(v.norm(), 2.0, 1e-12);
  // Ring r at polar pi (1 - r / rings): its height; vertex s at azimuth 2 pi s / segments.
  for (int r = 1; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const Eigen::Vector3d& v = mesh.vertices[1 + (r - 1) * segments + s];
      EXPECT_NEAR(v.z(), 2.0 * std::cos(M_PI * (1.0 - double(r) / rings)), 1e-12) << r << " " << s;
      EXPECT_NEAR(std::atan2(v.y(), v.x()), std::remainder(2.0 * M_PI * s / segments, 2.0 * M_PI),
                  1e-12)
          << r << " " << s;
    }
  }
}

TEST(UvSphere, IsClosedAndFacesOutwards) {
  const dc::TriangleMesh mesh = dc::uvSphere(16, 32, [](double, double) { return 0.5; });
  // Closed and consistently wound: every directed edge once, its reverse once.
  std::map<std::pair<int, int>, int> edges;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  }
  for (const auto& [edge, count] : edges) {
    EXPECT_EQ(count, 1) << edge.first << "-" << edge.second;
    EXPECT_EQ(edges.count({edge.second, edge.first}), 1u) << edge.first << "-" << edge.second;
  }
  // Outwards, and close to the ball's volume (an inscribed polyhedron: a little less).
  const double ball = 4.0 / 3.0 * M_PI * 0.125;
  EXPECT_GT(enclosedVolume(mesh), 0.97 * ball);
  EXPECT_LT(enclosedVolume(mesh), ball);
}

TEST(UvSphere, AsksTheRadiusOncePerVertexInVertexOrder) {
  const int rings = 3, segments = 4;
  std::vector<std::pair<double, double>> asked;
  const dc::TriangleMesh mesh = dc::uvSphere(rings, segments, [&](double polar, double azimuth) {
    asked.emplace_back(polar, azimuth);
    return 1.0 + polar;  // a blob: farther out towards the south
  });
  ASSERT_EQ(asked.size(), mesh.vertices.size());
  EXPECT_EQ(asked.front(), std::make_pair(M_PI, 0.0));
  EXPECT_EQ(asked.back(), std::make_pair(0.0, 0.0));
  for (size_t v = 0; v < asked.size(); ++v) {
    EXPECT_NEAR(mesh.vertices[v].norm(), 1.0 + asked[v].first, 1e-12) << v;
  }
}
