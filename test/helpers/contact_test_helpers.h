// Checks for contact between bodies that do not use the code they check: how deep a node is
// inside another body's closed surface, by its winding number and the distance to the nearest
// triangle, brute force over all nodes and triangles.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "body_meters.h"
#include "deformable_sim/core/bodies/body.h"
#include "deformable_sim/core/elements/mesh.h"

namespace deformable_sim::test {

/// Distance from p to the triangle abc (closest point by regions, as in Ericson's book).
inline double distanceToTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                 const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const Eigen::Vector3d q = p - n.dot(p - a) / n.squaredNorm() * n;
  const Eigen::Vector3d corners[3] = {a, b, c};
  bool inside = true;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d& u = corners[k];
    const Eigen::Vector3d& w = corners[(k + 1) % 3];
    if ((w - u).cross(q - u).dot(n) < 0.0) inside = false;
  }
  if (inside) return (p - q).norm();
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d& u = corners[k];
    const Eigen::Vector3d e = corners[(k + 1) % 3] - u;
    const double t = std::clamp(e.dot(p - u) / e.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (p - (u + t * e)).norm());
  }
  return best;
}

/// Winding number of the closed surface around p: 1 inside, 0 outside (solid angles, van
/// Oosterom and Strackee).
inline double windingNumber(const Eigen::Vector3d& p, const Eigen::VectorXd& x,
                            const std::vector<core::Triangle>& triangles) {
  double total = 0.0;
  for (const core::Triangle& t : triangles) {
    const Eigen::Vector3d a = x.segment<3>(3 * t[0]) - p, b = x.segment<3>(3 * t[1]) - p,
                          c = x.segment<3>(3 * t[2]) - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double numerator = a.dot(b.cross(c));
    const double denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    total += 2.0 * std::atan2(numerator, denominator);
  }
  return total / (4.0 * M_PI);
}

/// Distance from p to the closed surface (`x`: 3 per corner), negative inside, m.
inline double signedDistanceTo(const Eigen::Vector3d& p, const Eigen::VectorXd& x,
                               const std::vector<core::Triangle>& triangles) {
  double distance = std::numeric_limits<double>::infinity();
  for (const core::Triangle& t : triangles) {
    distance =
        std::min(distance, distanceToTriangle(p, x.segment<3>(3 * t[0]), x.segment<3>(3 * t[1]),
                                              x.segment<3>(3 * t[2])));
  }
  return windingNumber(p, x, triangles) < 0.5 ? distance : -distance;
}

/// The deepest any node of `nodes` is inside the closed surface of `solid`, m (0: none inside).
inline double deepestInside(const core::Body& nodes, const core::Body& solid) {
  const std::vector<core::Triangle> triangles = core::extractSurface(solid.mesh());
  double deepest = 0.0;
  for (int i = 0; i < nodes.numNodes(); ++i) {
    const Eigen::Vector3d p = nodes.positions().segment<3>(3 * i);
    deepest = std::max(deepest, -signedDistanceTo(p, solid.positions(), triangles));
  }
  return deepest;
}

}  // namespace deformable_sim::test
