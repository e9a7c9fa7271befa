#include "deformable_sim/core/contact/edge_edge.h"

#include <Eigen/Geometry>
#include <cmath>

namespace deformable_sim::core {

namespace {

/// Below this sine of the angle between them, two edges count as parallel.
constexpr double kParallelSine = 0.05;
/// The common normal must point out of each edge's body: within about 70 degrees of the direction
/// out of the one edge, and of the direction into the other. Two edges side by side in one plane
/// (a strip folded onto itself, seen at its rim) have a common normal along the rim, out of
/// neither: they do not cross each other, their faces touch.
constexpr double kOutwardCosine = 0.3;

/// Parameters s, t of the nearest points of the lines through edges a and b; false when they are
/// parallel.
bool nearestOnLines(const Eigen::Vector3d a[2], const Eigen::Vector3d b[2], double& s, double& t) {
  const Eigen::Vector3d ea = a[1] - a[0], eb = b[1] - b[0], r = a[0] - b[0];
  const double aa = ea.dot(ea), ab = ea.dot(eb), bb = eb.dot(eb);
  const double denominator = aa * bb - ab * ab;
  if (!(denominator > kParallelSine * kParallelSine * aa * bb)) return false;
  const double ar = ea.dot(r), br = eb.dot(r);
  s = (ab * br - bb * ar) / denominator;
  t = (aa * br - ab * ar) / denominator;
  return true;
}

/// Distance of a's nearest point in front of b's along `normal`.
double separation(const Eigen::Vector3d a[2], const Eigen::Vector3d b[2], double s, double t,
                  const Eigen::Vector3d& normal) {
  return normal.dot(a[0] + s * (a[1] - a[0]) - b[0] - t * (b[1] - b[0]));
}

}  // namespace

bool edgesMeet(const SweptEdge& a, const SweptEdge& b, const Eigen::Vector3d& outward_a,
               const Eigen::Vector3d& outward_b, double skin, double shallow, EdgeEdgeHit* hit) {
  double s = 0.0, t = 0.0;
  if (!nearestOnLines(a.end, b.end, s, t)) return false;
  if (!(s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0)) return false;
  Eigen::Vector3d normal = (a.end[1] - a.end[0]).cross(b.end[1] - b.end[0]).normalized();
  // Out of b's body and into a's: the way a's point must go to be clear of b.
  const Eigen::Vector3d out_a = outward_a.normalized(), out_b = outward_b.normalized();
  if (normal.dot(out_b) < 0.0) normal = -normal;
  if (!(normal.dot(out_b) >= kOutwardCosine && -normal.dot(out_a) >= kOutwardCosine)) return false;
  const double end_separation = separation(a.end, b.end, s, t, normal);
  if (!(end_separation < skin)) return false;
  // Where the pair was at the start, along the same normal (turned with the edges, if they did).
  double s0 = s, t0 = t;
  nearestOnLines(a.start, b.start, s0, t0);
  Eigen::Vector3d start_normal = (a.start[1] - a.start[0]).cross(b.start[1] - b.start[0]);
  if (start_normal.dot(normal) < 0.0) start_normal = -start_normal;
  const double length = start_normal.norm();
  const bool came_through = length > 0.0 && end_separation < 0.0 &&
                            separation(a.start, b.start, s0, t0, start_normal / length) >= -skin;
  // Deep behind from the start: the far sides of two bodies, not two edges that met.
  if (!came_through && -end_separation > shallow) return false;
  hit->depth = -end_separation;
  hit->normal = normal;
  hit->s = s;
  hit->t = t;
  return true;
}

}  // namespace deformable_sim::core
