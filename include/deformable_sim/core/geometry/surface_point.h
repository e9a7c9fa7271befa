// A point of a body's collision surface as a weighted sum of the body's nodes: a node, a point
// of an edge or a triangle, or, on a body made from a surface, a vertex of that surface (its
// cell's nodes, trilinear weights) or a point of one of its triangles (up to three cells).
#pragma once

#include <Eigen/Core>
#include <array>

namespace deformable_sim::core {

struct SurfacePoint {
  /// Three vertices of an embedded surface, eight nodes each, none shared.
  static constexpr int kMaxNodes = 24;
  std::array<int, kMaxNodes> nodes{};
  std::array<double, kMaxNodes> weights{};
  int count = 0;
  /// Its nodes move together when it is answered node by node (ContactParticipant's local
  /// answers): a vertex of an embedded surface, whose cell has nodes outside the surface that
  /// weigh next to nothing and, answering by their own masses, would take nearly all of it.
  bool shifts_cells = false;

  /// The point's value in a field given node by node, 3 per node (positions, velocities): the
  /// weighted sum of its nodes' values.
  Eigen::Vector3d of(const Eigen::VectorXd& field) const {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int k = 0; k < count; ++k) sum += weights[k] * field.segment<3>(3 * nodes[k]);
    return sum;
  }

  /// Adds `weight` times `other` (merging the nodes the two share).
  void add(const SurfacePoint& other, double weight) {
    for (int k = 0; k < other.count; ++k) {
      int at = 0;
      while (at < count && nodes[at] != other.nodes[k]) ++at;
      if (at == count) nodes[count] = other.nodes[k], weights[count++] = 0.0;
      weights[at] += weight * other.weights[k];
    }
    shifts_cells = shifts_cells || other.shifts_cells;
  }
};

}  // namespace deformable_sim::core
