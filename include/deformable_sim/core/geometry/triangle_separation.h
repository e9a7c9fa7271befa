// How far a triangle must move to leave a box or another triangle, by the separating axis
// theorem: of the face normals of both, the cross products of their edges (and, for triangles
// that lie in one plane, the normals of each one's edges within it), the axis along which their
// projections overlap least. That overlap is the least translation that parts them, exact for two
// convex shapes; a negative one is a gap (at least that wide). Contact uses it to find where the
// edges and corners of a box, or of a mesh's triangles, press into a body's faces between its
// nodes.
#pragma once

#include <Eigen/Geometry>

namespace deformable_sim::core {

struct TriangleSeparation {
  /// m: how far they overlap along `direction` (negative: the gap between them along it).
  double depth = 0.0;
  /// Unit: the way the triangle moves to leave the box.
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
};

/// The box of edge lengths `size` at `pose` (centred on its origin) and the triangle a, b, c,
/// world frame. A degenerate triangle is tested along the axes it still has.
TriangleSeparation separateFromBox(const Eigen::Isometry3d& pose, const Eigen::Vector3d& size,
                                   const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                   const Eigen::Vector3d& c);

/// The obstacle's triangle p, q, r and the moving triangle a, b, c, in one frame. A degenerate
/// triangle is tested along the axes it still has.
TriangleSeparation separateFromTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                                        const Eigen::Vector3d& r, const Eigen::Vector3d& a,
                                        const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace deformable_sim::core
