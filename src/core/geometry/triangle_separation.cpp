#include "deformable_sim/core/geometry/triangle_separation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace deformable_sim::core {

namespace {

/// Cross products shorter than this fraction of their factors' lengths are not axes (parallel
/// edges): the other axes decide.
constexpr double kParallel = 1e-9;

struct Axes {
  std::array<Eigen::Vector3d, 13> axis;
  int count = 0;
  void add(const Eigen::Vector3d& a, double scale) {
    const double length = a.norm();
    if (length > kParallel * scale) axis[count++] = a / length;
  }
};

}  // namespace

TriangleSeparation separateFromBox(const Eigen::Isometry3d& pose, const Eigen::Vector3d& size,
                                   const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                   const Eigen::Vector3d& c) {
  const Eigen::Matrix3d box_axes = pose.linear();
  const Eigen::Vector3d centre = pose.translation(), half = 0.5 * size;
  const std::array<Eigen::Vector3d, 3> edges{b - a, c - b, a - c};
  Axes axes;
  for (int j = 0; j < 3; ++j) axes.add(box_axes.col(j), 1.0);
  axes.add(edges[0].cross(edges[1]), edges[0].norm() * edges[1].norm());
  for (const Eigen::Vector3d& e : edges) {
    for (int j = 0; j < 3; ++j) axes.add(e.cross(box_axes.col(j)), e.norm());
  }
  TriangleSeparation least;
  least.depth = std::numeric_limits<double>::infinity();
  for (int k = 0; k < axes.count; ++k) {
    const Eigen::Vector3d& u = axes.axis[k];
    const double pa = u.dot(a), pb = u.dot(b), pc = u.dot(c);
    const double low = std::min({pa, pb, pc}), high = std::max({pa, pb, pc});
    const double reach = (box_axes.transpose() * u).cwiseAbs().dot(half);
    const double middle = u.dot(centre);
    // Out along +u: the triangle's low end past the box's high end; or along -u.
    const double up = middle + reach - low, down = high - (middle - reach);
    const double depth = std::min(up, down);
    if (depth < least.depth) {
      least.depth = depth;
      least.direction = up <= down ? u : Eigen::Vector3d(-u);
    }
  }
  return least;
}

double dentDepth(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                 const Eigen::Vector3d& inward, const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                 const Eigen::Vector3d& r) {
  // The triangle clipped by the face's three side planes (Sutherland-Hodgman): each plane cuts
  // a corner off at most, so three cuts leave at most six corners.
  std::array<Eigen::Vector3d, 9> polygon{p, q, r}, clipped;
  int count = 3;
  const std::array<Eigen::Vector3d, 3> face{a, b, c};
  for (int e = 0; e < 3 && count > 0; ++e) {
    const Eigen::Vector3d& from = face[e];
    Eigen::Vector3d side = inward.cross(face[(e + 1) % 3] - from);
    if (side.dot(face[(e + 2) % 3] - from) < 0.0) side = -side;  // towards the face's inside
    int kept = 0;
    for (int k = 0; k < count; ++k) {
      const Eigen::Vector3d& u = polygon[k];
      const Eigen::Vector3d& v = polygon[(k + 1) % count];
      const double du = side.dot(u - from), dv = side.dot(v - from);
      if (du >= 0.0) clipped[kept++] = u;
      if ((du < 0.0) != (dv < 0.0)) clipped[kept++] = u + du / (du - dv) * (v - u);
    }
    polygon = clipped;
    count = kept;
  }
  double deepest = -std::numeric_limits<double>::infinity();
  for (int k = 0; k < count; ++k) deepest = std::max(deepest, inward.dot(polygon[k] - a));
  return deepest;
}

EdgeDent edgeDent(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  const Eigen::Vector3d& inward, const Eigen::Vector3d& p,
                  const Eigen::Vector3d& q) {
  // The part p + s (q - p), s in [from, to], on the inner side of the face's three side planes.
  double from = 0.0, to = 1.0;
  const std::array<Eigen::Vector3d, 3> face{a, b, c};
  for (int e = 0; e < 3; ++e) {
    const Eigen::Vector3d& corner = face[e];
    Eigen::Vector3d side = inward.cross(face[(e + 1) % 3] - corner);
    if (side.dot(face[(e + 2) % 3] - corner) < 0.0) side = -side;  // towards the face's inside
    const double at_p = side.dot(p - corner), along = side.dot(q - p);
    if (along == 0.0) {
      if (at_p < 0.0) return {};
      continue;
    }
    const double crossing = -at_p / along;
    if (along > 0.0) {
      from = std::max(from, crossing);
    } else {
      to = std::min(to, crossing);
    }
  }
  if (!(from <= to)) return {};
  const Eigen::Vector3d start = p + from * (q - p), end = p + to * (q - p);
  const double start_depth = inward.dot(start - a), end_depth = inward.dot(end - a);
  // Deepest at a corner of the obstacle: there. Else the middle of the part: an edge across two
  // triangles of a body has a point in each, not one on the side they share.
  if (from == 0.0 && start_depth > end_depth) return {start_depth, start, true};
  if (to == 1.0 && end_depth > start_depth) return {end_depth, end, true};
  return {std::max(start_depth, end_depth), 0.5 * (start + end), false};
}

}  // namespace deformable_sim::core
