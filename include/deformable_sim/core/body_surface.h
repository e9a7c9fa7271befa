// The collision surface of a body: its boundary triangles (core/mesh.h extractSurface) and its
// feature edges (where the surface folds outwards), moving with its nodes, whatever its model
// (finite-element, pseudo-rigid or rigid). Each step it is swept from where the nodes were at the
// step's start to where they are now, and bounding-volume trees over the swept triangles and edges
// are refitted: the broad phase of contact between bodies and of a body with itself.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "deformable_sim/core/aabb_tree.h"
#include "deformable_sim/core/mesh.h"

namespace deformable_sim::core {

/// A feature edge of the surface: its two nodes, and the two triangles that share it.
struct SurfaceEdge {
  std::array<int, 2> nodes{};
  std::array<int, 2> triangles{};
};

class BodySurface {
 public:
  /// The surface of `mesh` at `positions` (3n). With `with_neighbours`, also which nodes share an
  /// element, so that self-contact can leave a node's own elements alone. Allocates.
  BodySurface(const Mesh& mesh, const Eigen::VectorXd& positions, bool with_neighbours);

  const std::vector<Triangle>& triangles() const { return triangles_; }
  /// The edges where the surface folds outwards (a convex ridge between two triangles that meet at
  /// more than kFeatureAngle, at rest): the only edges another surface can cross where neither
  /// has a node. An edge inside a flat or hollow part of the surface is reached through nodes
  /// and triangles.
  const std::vector<SurfaceEdge>& edges() const { return edges_; }
  /// Cosine of the feature angle: 25 degrees between the triangles' normals.
  static constexpr double kFeatureCosine = 0.9;
  /// The nodes on the surface, ascending: the only ones that can touch anything.
  const std::vector<int>& nodes() const { return nodes_; }
  /// Diagonal of the rest bounding box, m: the body's size for the contact tolerance.
  double size() const { return size_; }
  /// Shortest rest edge of a surface triangle, m: no part of the body is thinner.
  double shortestEdge() const { return shortest_edge_; }

  /// Sweeps the triangles and edges from the step's start positions to `positions` (3n),
  /// widened by `margin` (m), and refits the trees. Allocates nothing.
  void sweep(const Eigen::VectorXd& positions, double margin);
  /// The positions the next sweep starts from (3n); e.g. after the contact corrections.
  void setStart(const Eigen::VectorXd& positions) { start_ = positions; }
  const Eigen::VectorXd& start() const { return start_; }
  const AabbTree& tree() const { return tree_; }           ///< over the swept triangles
  const AabbTree& edgeTree() const { return edge_tree_; }  ///< over the swept edges

  /// Whether nodes a and b are one node or share an element (only with `with_neighbours`).
  bool adjacent(int a, int b) const;

 private:
  /// The feature edges among the triangles' edges, each once, from the rest positions.
  void findEdges(const std::vector<Eigen::Vector3d>& rest);

  std::vector<Triangle> triangles_;
  std::vector<SurfaceEdge> edges_;
  std::vector<int> nodes_;
  double size_ = 0.0, shortest_edge_ = 0.0;
  Eigen::VectorXd start_;
  std::vector<Box3> boxes_;       ///< swept box of each triangle
  std::vector<Box3> edge_boxes_;  ///< and of each edge
  AabbTree tree_, edge_tree_;
  /// Neighbours of node i (itself included, ascending): neighbours_[offsets_[i], offsets_[i+1]).
  std::vector<int> offsets_, neighbours_;
};

}  // namespace deformable_sim::core
