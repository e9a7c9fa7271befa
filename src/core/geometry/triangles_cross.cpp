#include "deformable_sim/core/geometry/triangles_cross.h"

#include <Eigen/Geometry>

namespace deformable_sim::core {

namespace {

// Six times the signed volume of the tetrahedron (a, b, c, d): > 0 when d is on the side of the
// plane of (a, b, c) that its counter-clockwise normal points to.
double orientation(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   const Eigen::Vector3d& d) {
  return (b - a).cross(c - a).dot(d - a);
}

// The segment p q passes through the inside of triangle (a, b, c): its ends strictly on either
// side of the plane, and the line through it strictly inside the three sides (the three
// tetrahedra of the line with each side turn the same way).
bool segmentPierces(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                    const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double dp = orientation(a, b, c, p);
  const double dq = orientation(a, b, c, q);
  if (!((dp > 0.0 && dq < 0.0) || (dp < 0.0 && dq > 0.0))) return false;
  const double s0 = orientation(p, q, a, b);
  const double s1 = orientation(p, q, b, c);
  const double s2 = orientation(p, q, c, a);
  return (s0 > 0.0 && s1 > 0.0 && s2 > 0.0) || (s0 < 0.0 && s1 < 0.0 && s2 < 0.0);
}

}  // namespace

bool trianglesCross(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& a2,
                    const Eigen::Vector3d& b0, const Eigen::Vector3d& b1,
                    const Eigen::Vector3d& b2) {
  return segmentPierces(a0, a1, b0, b1, b2) || segmentPierces(a1, a2, b0, b1, b2) ||
         segmentPierces(a2, a0, b0, b1, b2) || segmentPierces(b0, b1, a0, a1, a2) ||
         segmentPierces(b1, b2, a0, a1, a2) || segmentPierces(b2, b0, a0, a1, a2);
}

}  // namespace deformable_sim::core
