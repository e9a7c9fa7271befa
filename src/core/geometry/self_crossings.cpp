#include "deformable_sim/core/geometry/self_crossings.h"

#include <vector>

#include "deformable_sim/core/geometry/triangle_aabb_tree.h"
#include "deformable_sim/core/geometry/triangles_cross.h"

namespace deformable_sim::core {

namespace {

bool shareAVertex(const Eigen::Vector3i& a, const Eigen::Vector3i& b) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (a[i] == b[j]) return true;
    }
  }
  return false;
}

bool boxesOverlap(const TriangleMesh& surface, const Eigen::Vector3i& a, const Eigen::Vector3i& b) {
  const auto& v = surface.vertices;
  const Eigen::Vector3d a_min = v[a[0]].cwiseMin(v[a[1]]).cwiseMin(v[a[2]]);
  const Eigen::Vector3d a_max = v[a[0]].cwiseMax(v[a[1]]).cwiseMax(v[a[2]]);
  const Eigen::Vector3d b_min = v[b[0]].cwiseMin(v[b[1]]).cwiseMin(v[b[2]]);
  const Eigen::Vector3d b_max = v[b[0]].cwiseMax(v[b[1]]).cwiseMax(v[b[2]]);
  return (a_min.array() <= b_max.array()).all() && (b_min.array() <= a_max.array()).all();
}

}  // namespace

SelfCrossings selfCrossings(const TriangleMesh& surface, int max_candidates_per_triangle) {
  SelfCrossings found;
  const int n = static_cast<int>(surface.triangles.size());
  if (n < 2) return found;
  const TriangleAabbTree tree(surface);
  // Every candidate the tree gives is charged, whether or not it is then tested: many triangles
  // about one vertex (a fan) are each other's candidates but never a pair to test.
  const long budget = static_cast<long>(max_candidates_per_triangle) * n;
  std::vector<int> near;
  const auto& v = surface.vertices;
  for (int t = 0; t < n && found.complete; ++t) {
    const Eigen::Vector3i& a = surface.triangles[t];
    near.clear();
    tree.trianglesNear(v[a[0]].cwiseMin(v[a[1]]).cwiseMin(v[a[2]]),
                       v[a[0]].cwiseMax(v[a[1]]).cwiseMax(v[a[2]]), near);
    for (int u : near) {
      if (found.candidates == budget) {
        found.complete = false;
        break;
      }
      ++found.candidates;
      const Eigen::Vector3i& b = surface.triangles[u];
      if (u <= t || shareAVertex(a, b) || !boxesOverlap(surface, a, b)) continue;
      found.pairs += trianglesCross(v[a[0]], v[a[1]], v[a[2]], v[b[0]], v[b[1]], v[b[2]]);
    }
  }
  return found;
}

}  // namespace deformable_sim::core
