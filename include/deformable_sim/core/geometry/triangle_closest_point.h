// The point of a triangle nearest to a given point, and which feature of the triangle it lies on
// (a corner, an edge or the inside): the sign of a mesh's distance depends on that feature.
#pragma once

#include <Eigen/Core>

namespace deformable_sim::core {

struct TriangleClosestPoint {
  enum class Feature { kVertex, kEdge, kFace };
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Feature feature = Feature::kFace;
  /// kVertex: the corner (0, 1, 2); kEdge: the edge from corner `index` to corner index + 1 mod 3.
  int index = 0;
};

/// Nearest point to `p` of the triangle a, b, c (not degenerate).
TriangleClosestPoint closestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                            const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace deformable_sim::core
