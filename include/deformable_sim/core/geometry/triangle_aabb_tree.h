// A bounding-box tree over a fixed set of triangles, built once, for nearest-point queries that
// allocate nothing (a static obstacle's mesh is queried for every node at every step) and for the
// triangles near a box (a surface's check for where it crosses itself).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "deformable_sim/core/geometry/triangle_closest_point.h"
#include "deformable_sim/core/geometry/triangle_mesh.h"

namespace deformable_sim::core {

class TriangleAabbTree {
 public:
  struct Nearest {
    int triangle = -1;
    TriangleClosestPoint closest;
    double squared_distance = 0.0;
  };

  TriangleAabbTree() = default;  ///< empty, until assigned a built one
  /// Builds the tree over `mesh`'s triangles (at least one, none degenerate).
  explicit TriangleAabbTree(const TriangleMesh& mesh);

  /// The point of `mesh` (the one the tree was built over) nearest to `p`.
  Nearest nearest(const TriangleMesh& mesh, const Eigen::Vector3d& p) const;

  /// Appends to `found` the triangles of every leaf whose box meets the box [min, max]: all the
  /// triangles whose own box meets it, and maybe a few more. Allocates only as `found` grows.
  void trianglesNear(const Eigen::Vector3d& min, const Eigen::Vector3d& max,
                     std::vector<int>& found) const;

 private:
  struct Node {
    Eigen::Vector3d min, max;
    int first = 0;  ///< leaf: first entry of order_; inner: index of the first child
    int count = 0;  ///< leaf: number of triangles; inner: 0 (the children are first, first + 1)
  };

  int build(const TriangleMesh& mesh, int index, int begin, int end);

  std::vector<Node> nodes_;                 ///< nodes_[0] is the root
  std::vector<int> order_;                  ///< triangle indices, each leaf's a contiguous range
  std::vector<Eigen::Vector3d> centroids_;  ///< only while building
};

}  // namespace deformable_sim::core
