#include "deformable_sim/core/triangle_mesh.h"

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

}  // namespace deformable_sim::core
