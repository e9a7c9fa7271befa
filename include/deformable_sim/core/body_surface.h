// The collision surface of a body: its boundary triangles (core/mesh.h extractSurface), moving
// with its nodes, whatever its model (finite-element, pseudo-rigid or rigid). Each step it is
// swept from where the nodes were at the step's start to where they are now, and a bounding-volume
// tree over the swept triangles is refitted: the broad phase of contact between bodies and of a
// body with itself.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "deformable_sim/core/aabb_tree.h"
#include "deformable_sim/core/mesh.h"

namespace deformable_sim::core {

class BodySurface {
 public:
  /// The surface of `mesh` at `positions` (3n). With `with_neighbours`, also which nodes share an
  /// element, so that self-contact can leave a node's own elements alone. Allocates.
  BodySurface(const Mesh& mesh, const Eigen::VectorXd& positions, bool with_neighbours);

  const std::vector<Triangle>& triangles() const { return triangles_; }
  /// The nodes on the surface, ascending: the only ones that can touch anything.
  const std::vector<int>& nodes() const { return nodes_; }
  /// Diagonal of the rest bounding box, m: the body's size for the contact tolerance.
  double size() const { return size_; }
  /// Shortest rest edge of a surface triangle, m: no part of the body is thinner.
  double shortestEdge() const { return shortest_edge_; }

  /// Sweeps the triangles from the step's start positions to `positions` (3n), widened by
  /// `margin` (m), and refits the tree. Allocates nothing.
  void sweep(const Eigen::VectorXd& positions, double margin);
  /// The positions the next sweep starts from (3n); e.g. after the contact corrections.
  void setStart(const Eigen::VectorXd& positions) { start_ = positions; }
  const Eigen::VectorXd& start() const { return start_; }
  const AabbTree& tree() const { return tree_; }

  /// Whether nodes a and b are one node or share an element (only with `with_neighbours`).
  bool adjacent(int a, int b) const;

 private:
  std::vector<Triangle> triangles_;
  std::vector<int> nodes_;
  double size_ = 0.0, shortest_edge_ = 0.0;
  Eigen::VectorXd start_;
  std::vector<Box3> boxes_;  ///< swept box of each triangle
  AabbTree tree_;
  /// Neighbours of node i (itself included, ascending): neighbours_[offsets_[i], offsets_[i+1]).
  std::vector<int> offsets_, neighbours_;
};

}  // namespace deformable_sim::core
