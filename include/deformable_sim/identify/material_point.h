// A material point of a body: where a tracked marker sits, found by its rest position and followed
// as the weighted sum of its element's nodes.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "deformable_sim/core/elements/mesh.h"

namespace deformable_sim::identify {

struct MaterialPoint {
  std::vector<int> nodes;
  std::vector<double> weights;  ///< the element's shape functions at the point; sum to 1

  /// Where the point is, given the body's positions (3n, world).
  Eigen::Vector3d position(const Eigen::VectorXd& positions) const;
};

/// The point at rest position `at` (m): in a tetrahedron (barycentric weights) or a cell (its
/// shape functions, natural coordinates by Newton's method). None when no element holds it
/// (`tolerance`, m, of slack on the element's boundary).
std::optional<MaterialPoint> findMaterialPoint(const core::Mesh& mesh, const Eigen::Vector3d& at,
                                               double tolerance = 1.0e-6);

}  // namespace deformable_sim::identify
