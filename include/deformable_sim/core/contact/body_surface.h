// The collision surface of a body: its boundary triangles (core/elements/mesh.h extractSurface) and
// its feature edges (where the surface folds outwards), moving with its nodes, whatever its model
// (finite-element, pseudo-rigid or rigid); for a body made from a surface, the triangles of that
// surface, whose corners are its vertices, each moving with its cell's nodes
// (core/surface_bodies/embedded_surface.h). Each step it is swept from where the corners were at
// the step's start to where they are now, and bounding-volume trees over the swept triangles and
// edges are refitted: the broad phase of contact between bodies and of a body with itself.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "deformable_sim/core/contact/aabb_tree.h"
#include "deformable_sim/core/elements/mesh.h"
#include "deformable_sim/core/geometry/surface_point.h"
#include "deformable_sim/core/surface_bodies/embedded_surface.h"

namespace deformable_sim::core {

/// A feature edge of the surface: its two corners, and the two triangles that share it.
struct SurfaceEdge {
  std::array<int, 2> nodes{};
  std::array<int, 2> triangles{};
};

/// A point of the surface as a weighed sum of its corners: a corner (one), an edge's point (two),
/// a triangle's (three). Its corners, unlike its nodes, are the same from step to step, so what a
/// body readies for them may be kept (ContactParticipant::keepCorner).
struct SurfaceCorners {
  int count = 0;
  std::array<int, 3> ids{};
  std::array<double, 3> weights{};
};

class BodySurface {
 public:
  /// The surface of `mesh` at `positions` (3n): its corners are the nodes. With
  /// `with_neighbours`, also which nodes share an element, so that self-contact can leave a
  /// node's own elements alone. Allocates.
  BodySurface(const Mesh& mesh, const Eigen::VectorXd& positions, bool with_neighbours);
  /// The surface a body was made from, its grid's nodes at `positions` (3n): its corners are the
  /// surface's vertices. Allocates.
  BodySurface(const EmbeddedSurface& surface, const Eigen::VectorXd& positions);

  /// Triangles of corners (node numbers, or vertex numbers of an embedded surface).
  const std::vector<Triangle>& triangles() const { return triangles_; }
  /// The edges where the surface folds outwards (a convex ridge between two triangles that meet at
  /// more than kFeatureAngle, at rest): the only edges another surface can cross where neither
  /// has a corner. An edge inside a flat or hollow part of the surface is reached through corners
  /// and triangles.
  const std::vector<SurfaceEdge>& edges() const { return edges_; }
  /// Whether the side of triangle t from its corner k to corner k + 1 is one of edges().
  bool fold(int t, int k) const { return folds_[t][k]; }
  /// Cosine of the feature angle: 25 degrees between the triangles' normals.
  static constexpr double kFeatureCosine = 0.9;
  /// The corners on the surface, ascending: the only points that can touch anything first.
  const std::vector<int>& nodes() const { return nodes_; }
  /// Corner c as a point of the body: a node, or a vertex on its cell's nodes.
  SurfacePoint corner(int c) const;
  /// The point of triangle t with barycentric `weights`, and of an edge a fraction s along it.
  SurfacePoint trianglePoint(const Triangle& t, const std::array<double, 3>& weights) const;
  SurfacePoint edgePoint(const SurfaceEdge& edge, double s) const;
  /// Diagonal of the rest bounding box, m: the body's size for the contact tolerance.
  double size() const { return size_; }
  /// Shortest rest edge of a surface triangle, m: no part of the body is thinner.
  double shortestEdge() const { return shortest_edge_; }

  /// Sweeps the triangles and edges from the step's start to the body's node positions (3n),
  /// widened by `margin` (m), and refits the trees. Allocates nothing.
  void sweep(const Eigen::VectorXd& positions, double margin);
  /// The node positions the next sweep starts from (3n); e.g. after the contact corrections.
  void setStart(const Eigen::VectorXd& positions);
  /// Where the corners were at the step's start (3 per corner), and the nodes (3n).
  const Eigen::VectorXd& start() const { return embedded_ ? corner_start_ : start_; }
  const Eigen::VectorXd& nodeStart() const { return start_; }
  /// Where corner c was at the last sweep (its end).
  Eigen::Vector3d now(int c) const { return corners_now_.segment<3>(3 * c); }
  /// Out of the body at corner c at the last sweep: the sum of its triangles' normals, each as
  /// long as twice its area (zero for a corner on no triangle).
  Eigen::Vector3d outwardAt(int c) const;
  const AabbTree& tree() const { return tree_; }           ///< over the swept triangles
  const AabbTree& edgeTree() const { return edge_tree_; }  ///< over the swept edges

  /// Whether corners a and b are one or share an element (nodes, only with `with_neighbours`),
  /// or a cell node (vertices of an embedded surface).
  bool adjacent(int a, int b) const;

 private:
  /// Size, shortest edge, corners, trees and feature edges from the corners' rest positions and
  /// where they are now (3 per corner).
  void build(const std::vector<Eigen::Vector3d>& rest, const Eigen::VectorXd& corners);
  /// The feature edges among the triangles' edges, each once, from the rest positions.
  void findEdges(const std::vector<Eigen::Vector3d>& rest);
  /// Corner positions (3 per corner) from node positions (3n): an embedded surface's vertices.
  void placeCorners(const Eigen::VectorXd& positions, Eigen::VectorXd& corners) const;

  std::vector<Triangle> triangles_;
  std::vector<SurfaceEdge> edges_;
  std::vector<std::array<bool, 3>> folds_;  ///< see fold()
  std::vector<int> nodes_;
  /// The triangles at corner c: corner_triangles_[triangles_at_[c], triangles_at_[c + 1]).
  std::vector<int> triangles_at_, corner_triangles_;
  double size_ = 0.0, shortest_edge_ = 0.0;
  Eigen::VectorXd start_;  ///< node positions at the step's start
  /// An embedded surface: each vertex on its cell's nodes, and the vertices at the step's start.
  bool embedded_ = false;
  std::vector<SurfacePoint> vertices_;
  Eigen::VectorXd corner_start_;
  Eigen::VectorXd corners_now_;   ///< the corners at the last sweep
  std::vector<Box3> boxes_;       ///< swept box of each triangle
  std::vector<Box3> edge_boxes_;  ///< and of each edge
  AabbTree tree_, edge_tree_;
  /// Neighbours of node i (itself included, ascending): neighbours_[offsets_[i], offsets_[i+1]).
  std::vector<int> offsets_, neighbours_;
};

}  // namespace deformable_sim::core
