// Measures of a triangle surface for the geometry tests, computed independently of the code under
// test: the volume it encloses by the divergence theorem, its area, and how often each directed
// edge is used.
#pragma once

#include <Eigen/Geometry>
#include <map>
#include <utility>

#include "deformable_sim/core/geometry/triangle_mesh.h"

namespace deformable_sim::test {

/// Sum over the triangles of the signed volume of (origin, a, b, c): the volume enclosed by a
/// closed surface facing outwards (negative facing inwards), independent of the origin.
inline double divergenceVolume(const core::TriangleMesh& mesh) {
  double volume = 0.0;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    volume += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]])) / 6.0;
  }
  return volume;
}

/// The area vector of triangle t: half the cross product of its sides, along its normal.
inline Eigen::Vector3d areaVector(const core::TriangleMesh& mesh, int t) {
  const Eigen::Vector3i& c = mesh.triangles[t];
  const Eigen::Vector3d& a = mesh.vertices[c[0]];
  return 0.5 * (mesh.vertices[c[1]] - a).cross(mesh.vertices[c[2]] - a);
}

/// The total area of the triangles, m^2.
inline double surfaceArea(const core::TriangleMesh& mesh) {
  double area = 0.0;
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
    area += areaVector(mesh, t).norm();
  }
  return area;
}

/// How often each directed edge (from, to) is used by the triangles.
inline std::map<std::pair<int, int>, int> directedEdges(const core::TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> edges;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  }
  return edges;
}

}  // namespace deformable_sim::test
