#include "deformable_sim/core/geometry/triangle_mesh.h"

#include <stdexcept>

namespace deformable_sim::core {

TriangleMesh boxSurface(const Eigen::Vector3d& min, const Eigen::Vector3d& max) {
  TriangleMesh mesh;
  for (int c = 0; c < 8; ++c) {
    mesh.vertices.emplace_back((c & 1) ? max.x() : min.x(), (c & 2) ? max.y() : min.y(),
                               (c & 4) ? max.z() : min.z());
  }
  // Each face's quad, counter-clockwise seen from outside: z = min, z = max, y = min, y = max,
  // x = min, x = max.
  constexpr int kQuads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : kQuads) {
    mesh.triangles.emplace_back(q[0], q[1], q[2]);
    mesh.triangles.emplace_back(q[0], q[2], q[3]);
  }
  return mesh;
}

void flatten(const TriangleMesh& mesh, std::vector<double>& vertices,
             std::vector<uint32_t>& triangles) {
  for (const Eigen::Vector3d& v : mesh.vertices)
    vertices.insert(vertices.end(), {v.x(), v.y(), v.z()});
  for (const Eigen::Vector3i& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) triangles.push_back(static_cast<uint32_t>(t[k]));
  }
}

TriangleMesh unflatten(const std::vector<double>& vertices, const std::vector<uint32_t>& triangles,
                       const std::string& what) {
  if (vertices.size() % 3 != 0 || triangles.size() % 3 != 0) {
    throw std::invalid_argument(what + ": its vertices and triangles must come in threes");
  }
  TriangleMesh mesh;
  for (size_t k = 0; k < vertices.size(); k += 3) {
    mesh.vertices.emplace_back(vertices[k], vertices[k + 1], vertices[k + 2]);
  }
  for (size_t k = 0; k < triangles.size(); k += 3) {
    for (int c = 0; c < 3; ++c) {
      if (triangles[k + c] >= mesh.vertices.size()) {
        throw std::invalid_argument(what + ": a triangle refers to vertex " +
                                    std::to_string(triangles[k + c]) + " of " +
                                    std::to_string(mesh.vertices.size()));
      }
    }
    mesh.triangles.emplace_back(triangles[k], triangles[k + 1], triangles[k + 2]);
  }
  return mesh;
}

}  // namespace deformable_sim::core
