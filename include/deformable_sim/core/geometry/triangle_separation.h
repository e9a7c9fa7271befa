// How a body's face, a triangle, meets an obstacle's edges and corners: the least translation
// that takes it out of a box, by the separating axis theorem (of the box's three face normals,
// the triangle's normal and the nine cross products of their edges, the axis along which their
// projections overlap least; exact for two convex shapes, and a negative overlap is a gap at least
// that wide); and how far one of a mesh's triangles reaches behind it within its outline, along
// its normal (the dent that triangle's edge or corner makes). Contact uses both to find where
// obstacles press into a body's faces between its nodes.
#pragma once

#include <Eigen/Geometry>
#include <limits>

namespace deformable_sim::core {

struct TriangleSeparation {
  /// m: how far they overlap along `direction` (negative: the gap between them along it).
  double depth = 0.0;
  /// Unit: the way the triangle moves to leave the obstacle.
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
};

/// The box of edge lengths `size` at `pose` (centred on its origin) and the triangle a, b, c,
/// world frame. A degenerate triangle is tested along the axes it still has.
TriangleSeparation separateFromBox(const Eigen::Isometry3d& pose, const Eigen::Vector3d& size,
                                   const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                   const Eigen::Vector3d& c);

/// How far the triangle p, q, r reaches behind the face a, b, c along `inward` (the face's unit
/// normal into the body), counting only its part within the face's outline seen along that
/// normal: negative when that part is all in front (the gap), -infinity when no part is within
/// the outline. Allocates nothing.
double dentDepth(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                 const Eigen::Vector3d& inward, const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                 const Eigen::Vector3d& r);

struct EdgeDent {
  /// m: how far the edge reaches behind the face (negative: the gap; -infinity: no part of the
  /// edge is within the face's outline).
  double depth = -std::numeric_limits<double>::infinity();
  /// Where it presses: the edge's end (the obstacle's corner) where that is the deepest within
  /// the outline, else the middle of its part within the outline.
  Eigen::Vector3d at = Eigen::Vector3d::Zero();
  bool at_corner = false;  ///< `at` is the edge's end
};

/// How far the edge p, q reaches behind the face a, b, c along `inward` (the face's unit normal
/// into the body), counting only its part within the face's outline seen along that normal: the
/// dent an obstacle's edge makes in a body's face between its corners.
EdgeDent edgeDent(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  const Eigen::Vector3d& inward, const Eigen::Vector3d& p,
                  const Eigen::Vector3d& q);

}  // namespace deformable_sim::core
