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
  std::array<Eigen::Vector3d, 17> axis;
  int count = 0;
  void add(const Eigen::Vector3d& a, double scale) {
    const double length = a.norm();
    if (length > kParallel * scale) axis[count++] = a / length;
  }
};

/// Of `axes`, the one along which the triangle a, b, c and the obstacle overlap least, and by
/// how much; `extent(u)` is the obstacle's interval along u (low, high).
template <typename Extent>
TriangleSeparation leastOverlap(const Axes& axes, const Extent& extent, const Eigen::Vector3d& a,
                                const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  TriangleSeparation least;
  least.depth = std::numeric_limits<double>::infinity();
  for (int k = 0; k < axes.count; ++k) {
    const Eigen::Vector3d& u = axes.axis[k];
    const double pa = u.dot(a), pb = u.dot(b), pc = u.dot(c);
    const double low = std::min({pa, pb, pc}), high = std::max({pa, pb, pc});
    const Eigen::Vector2d obstacle = extent(u);
    // Out along +u: the triangle's low end past the obstacle's high end; or along -u.
    const double up = obstacle[1] - low, down = high - obstacle[0];
    const double depth = std::min(up, down);
    if (depth < least.depth) {
      least.depth = depth;
      least.direction = up <= down ? u : Eigen::Vector3d(-u);
    }
  }
  return least;
}

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
  const auto extent = [&](const Eigen::Vector3d& u) {
    const double reach = (box_axes.transpose() * u).cwiseAbs().dot(half);
    const double middle = u.dot(centre);
    return Eigen::Vector2d(middle - reach, middle + reach);
  };
  return leastOverlap(axes, extent, a, b, c);
}

TriangleSeparation separateFromTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                                        const Eigen::Vector3d& r, const Eigen::Vector3d& a,
                                        const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const std::array<Eigen::Vector3d, 3> mine{b - a, c - b, a - c}, theirs{q - p, r - q, p - r};
  const Eigen::Vector3d my_normal = mine[0].cross(mine[1]);
  const Eigen::Vector3d their_normal = theirs[0].cross(theirs[1]);
  Axes axes;
  axes.add(their_normal, theirs[0].norm() * theirs[1].norm());
  axes.add(my_normal, mine[0].norm() * mine[1].norm());
  for (const Eigen::Vector3d& e : mine) {
    for (const Eigen::Vector3d& f : theirs) axes.add(e.cross(f), e.norm() * f.norm());
  }
  // In one plane the crosses all lie along its normal: the edges' normals within it part them.
  for (const Eigen::Vector3d& f : theirs)
    axes.add(their_normal.cross(f), their_normal.norm() * f.norm());
  for (const Eigen::Vector3d& e : mine) axes.add(my_normal.cross(e), my_normal.norm() * e.norm());
  const auto extent = [&](const Eigen::Vector3d& u) {
    const double pp = u.dot(p), pq = u.dot(q), pr = u.dot(r);
    return Eigen::Vector2d(std::min({pp, pq, pr}), std::max({pp, pq, pr}));
  };
  return leastOverlap(axes, extent, a, b, c);
}

}  // namespace deformable_sim::core
