#include "deformable_sim/core/surface_inset.h"

#include <Eigen/Geometry>
#include <cmath>

#include "deformable_sim/core/triangle_aabb_tree.h"
#include "deformable_sim/core/winding_number.h"

namespace deformable_sim::core {

namespace {

// The triangles with an area: the nearest-point tree takes no degenerate one, and a degenerate
// triangle is no nearer than its neighbours.
TriangleMesh withoutDegenerateTriangles(const TriangleMesh& surface) {
  TriangleMesh kept{surface.vertices, {}};
  for (const Eigen::Vector3i& t : surface.triangles) {
    const Eigen::Vector3d& a = surface.vertices[t[0]];
    const Eigen::Vector3d twice_area =
        (surface.vertices[t[1]] - a).cross(surface.vertices[t[2]] - a);
    if (twice_area.norm() > 0.0) kept.triangles.push_back(t);
  }
  return kept;
}

}  // namespace

std::vector<double> surfaceInsets(const Mesh& mesh, const TriangleMesh& surface) {
  std::vector<double> insets(mesh.numNodes(), 0.0);
  const TriangleMesh triangles = withoutDegenerateTriangles(surface);
  if (triangles.triangles.empty()) return insets;
  const WindingNumber winding(triangles);
  const TriangleAabbTree tree(triangles);
  for (int i = 0; i < mesh.numNodes(); ++i) {
    const Eigen::Vector3d& node = mesh.positions[i];
    if (winding.at(node) >= 0.5) continue;
    insets[i] = std::sqrt(tree.nearest(triangles, node).squared_distance);
  }
  return insets;
}

}  // namespace deformable_sim::core
