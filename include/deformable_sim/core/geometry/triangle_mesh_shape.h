// A triangle mesh as a collision shape: the signed distance of a point to it, with the nearest
// surface point and the outward normal there, as for the primitive shapes.
//
// A closed mesh (every edge shared by two triangles, turned consistently) is a solid: a point is
// inside when it lies behind the angle-weighted pseudo-normal of the nearest feature (face, edge
// or corner), which decides the side exactly (Baerentzen and Aanaes, 2005). An inward-turned
// closed mesh is turned outward.
//
// An open mesh (a table top, a single wall) is a shell whose front is the side its triangles face
// (counter-clockwise seen from the front). A point behind a triangle by less than open_depth
// counts as inside and is pushed out to the front; farther behind, or beyond a free edge, it is
// free. So a node that reaches the back within a step or two is caught, while the space well
// behind the mesh stays open.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "deformable_sim/core/geometry/triangle_aabb_tree.h"
#include "deformable_sim/core/geometry/triangle_mesh.h"

namespace deformable_sim::core {

class TriangleMeshShape {
 public:
  static constexpr double kDefaultOpenDepth = 0.02;  ///< m

  /// Validates `mesh` (finite vertices, valid indices, no zero-area triangle, no edge used twice
  /// in the same direction) and builds the tree; throws std::invalid_argument saying what is
  /// wrong.
  explicit TriangleMeshShape(TriangleMesh mesh, double open_depth = kDefaultOpenDepth);

  const TriangleMesh& mesh() const { return mesh_; }
  bool closed() const { return closed_; }
  double openDepth() const { return open_depth_; }

  /// Signed distance from `p` (negative inside), the nearest surface point and the outward
  /// normal there, in the mesh's frame. Allocates nothing.
  double signedDistance(const Eigen::Vector3d& p, Eigen::Vector3d* surface = nullptr,
                        Eigen::Vector3d* normal = nullptr) const;
  /// The mesh's bounding box, in its frame.
  const Eigen::AlignedBox3d& bounds() const { return bounds_; }
  /// Whether the edge of triangle t from its corner k to corner k + 1 is a ridge of the surface
  /// (a free edge, or a convex fold of more than kRidgeAngle) that t speaks for: each ridge is
  /// spoken for by one of its two triangles.
  bool ridge(int t, int k) const { return ridges_[t][k]; }
  /// The triangle across that edge (-1 on a free edge), and triangle t's outward unit normal.
  int across(int t, int k) const { return neighbours_[t][k]; }
  const Eigen::Vector3d& faceNormal(int t) const { return face_normals_[t]; }
  /// Radians between two triangles' normals beyond which their edge is a ridge: flatter, it is
  /// a curved surface's facet edge, or a flat face's diagonal.
  static constexpr double kRidgeAngle = 0.175;  // 10 degrees
  /// Appends to `out` the triangles whose boxes meet the box lower..upper (the mesh's frame).
  void trianglesNear(const Eigen::Vector3d& lower, const Eigen::Vector3d& upper,
                     std::vector<int>& out) const {
    tree_.trianglesNear(lower, upper, out);
  }
  /// How deep the mesh's edges and corners dent the triangle a, b, c (the mesh's frame) along
  /// `inward`, its unit normal into the body: the deepest dentDepth()
  /// (core/geometry/triangle_separation.h) of the mesh's triangles within `margin` of it;
  /// negative, the gap to the nearest; -infinity when none is near. `near` is room for the
  /// triangles looked at; allocates only as it grows.
  double dent(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
              const Eigen::Vector3d& inward, double margin, std::vector<int>& near) const;

 private:
  void findNeighbours();
  void computePseudoNormals();
  void findRidges();

  TriangleMesh mesh_;
  double open_depth_;
  bool closed_ = false;
  /// For each triangle edge k (corner k to k + 1): the triangle across it, -1 on a free edge.
  std::vector<std::array<int, 3>> neighbours_;
  std::vector<Eigen::Vector3d> face_normals_;
  std::vector<std::array<Eigen::Vector3d, 3>> edge_normals_;  ///< zero on a free edge
  std::vector<Eigen::Vector3d> vertex_normals_;  ///< angle-weighted; zero on a free edge's corner
  std::vector<std::array<bool, 3>> ridges_;      ///< see ridge()
  TriangleAabbTree tree_;
  Eigen::AlignedBox3d bounds_;
};

}  // namespace deformable_sim::core
