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

  TriangleMesh mesh_;
  double open_depth_;
  bool closed_ = false;
  /// For each triangle edge k (corner k to k + 1): the triangle across it, -1 on a free edge.
  std::vector<std::array<int, 3>> neighbours_;
  std::vector<Eigen::Vector3d> face_normals_;
  std::vector<std::array<Eigen::Vector3d, 3>> edge_normals_;  ///< zero on a free edge
  std::vector<Eigen::Vector3d> vertex_normals_;  ///< angle-weighted; zero on a free edge's corner
  TriangleAabbTree tree_;
  Eigen::AlignedBox3d bounds_;
};

}  // namespace deformable_sim::core
