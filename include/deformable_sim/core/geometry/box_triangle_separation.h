// How far a triangle must move to leave a box, by the separating axis theorem: of the box's
// three face normals, the triangle's normal and the nine cross products of their edges, the axis
// along which their projections overlap least. That overlap is the least translation that parts
// them, exact for two convex shapes; a negative one is a gap (at least that wide). Contact uses it
// to find where a box's edges and corners press into a body's faces between its nodes.
#pragma once

#include <Eigen/Geometry>

namespace deformable_sim::core {

struct BoxTriangleSeparation {
  /// m: how far they overlap along `direction` (negative: the gap between them along it).
  double depth = 0.0;
  /// Unit: the way the triangle moves to leave the box.
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
};

/// The box of edge lengths `size` at `pose` (centred on its origin) and the triangle a, b, c,
/// world frame. A degenerate triangle is tested along the axes it still has.
BoxTriangleSeparation separateFromBox(const Eigen::Isometry3d& pose, const Eigen::Vector3d& size,
                                      const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                      const Eigen::Vector3d& c);

}  // namespace deformable_sim::core
