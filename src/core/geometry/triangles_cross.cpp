#include "deformable_sim/core/geometry/triangles_cross.h"

#include <Eigen/Geometry>

namespace deformable_sim::core {

namespace {

// The side of the plane of (a, b, c) that d is on: +1 where its counter-clockwise normal points,
// -1 the other, 0 within round-off of it. Six times the signed volume of the tetrahedron, against
// a bound relative to its edges: a surface read as floats and then turned into place puts a
// vertex of one flat strip within 1e-22 m³ of its neighbour's plane, whose sign is noise (the
// shipped sponge "crossed itself" so in the pile).
int side(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
         const Eigen::Vector3d& d) {
  constexpr double kRoundOff = 1e-12;  // relative; double round-off is ~1e-16
  const Eigen::Vector3d ab = b - a, ac = c - a, ad = d - a;
  const double volume = ab.cross(ac).dot(ad);
  const double bound = kRoundOff * ab.norm() * ac.norm() * ad.norm();
  return volume > bound ? 1 : volume < -bound ? -1 : 0;
}

// The segment p q passes through the inside of triangle (a, b, c): its ends strictly on either
// side of the plane, and the line through it strictly inside the three sides (the three
// tetrahedra of the line with each side turn the same way, none flat).
bool segmentPierces(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                    const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const int dp = side(a, b, c, p), dq = side(a, b, c, q);
  if (dp * dq >= 0) return false;
  const int s0 = side(p, q, a, b), s1 = side(p, q, b, c), s2 = side(p, q, c, a);
  return s0 != 0 && s0 == s1 && s1 == s2;
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
