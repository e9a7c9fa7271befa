#include "deformable_sim/core/geometry/triangle_closest_point.h"

namespace deformable_sim::core {

namespace {

TriangleClosestPoint at(const Eigen::Vector3d& point, TriangleClosestPoint::Feature feature,
                        int index) {
  TriangleClosestPoint result;
  result.point = point;
  result.feature = feature;
  result.index = index;
  return result;
}

}  // namespace

// The Voronoi regions of the corners, then of the edges, then the inside, tested with the
// barycentric signs of Ericson's "Real-Time Collision Detection" (5.1.5).
TriangleClosestPoint closestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                            const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  using Feature = TriangleClosestPoint::Feature;
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return at(a, Feature::kVertex, 0);
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return at(b, Feature::kVertex, 1);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    return at(a + d1 / (d1 - d3) * ab, Feature::kEdge, 0);
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return at(c, Feature::kVertex, 2);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    return at(a + d2 / (d2 - d6) * ac, Feature::kEdge, 2);  // edge c-a
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    return at(b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b), Feature::kEdge, 1);
  }
  const double denominator = 1.0 / (va + vb + vc);
  return at(a + ab * (vb * denominator) + ac * (vc * denominator), Feature::kFace, 0);
}

}  // namespace deformable_sim::core
