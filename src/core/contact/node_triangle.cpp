#include "deformable_sim/core/contact/node_triangle.h"

#include <Eigen/Geometry>
#include <algorithm>

namespace deformable_sim::core {

namespace {

/// Foot points this close outside an edge (in barycentric units) still count as on the
/// triangle, so that a node on an edge shared by two triangles touches at least one of them.
constexpr double kEdgeSlack = 1e-6;

/// Barycentric slack for a node `depth` behind the plane: behind a ridge between two triangles
/// its foot point can lie outside both by about its depth; up to that it is on the triangle.
double slackFor(const Eigen::Vector3d corners[3], double depth) {
  const double longest =
      std::max({(corners[1] - corners[0]).norm(), (corners[2] - corners[1]).norm(),
                (corners[0] - corners[2]).norm()});
  const double twice_area = (corners[1] - corners[0]).cross(corners[2] - corners[0]).norm();
  return std::max(kEdgeSlack, depth * longest / twice_area);
}

/// Unit normal of the triangle and the distance of p in front of its plane; false when it has no
/// area.
bool planeDistance(const Eigen::Vector3d corners[3], const Eigen::Vector3d& p,
                   Eigen::Vector3d& normal, double& distance) {
  normal = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
  const double twice_area = normal.norm();
  if (!(twice_area > 0.0)) return false;
  normal /= twice_area;
  distance = normal.dot(p - corners[0]);
  return true;
}

/// Barycentric coordinates of q (in the triangle's plane).
Eigen::Vector3d barycentric(const Eigen::Vector3d corners[3], const Eigen::Vector3d& q) {
  const Eigen::Vector3d e1 = corners[1] - corners[0], e2 = corners[2] - corners[0];
  const Eigen::Vector3d r = q - corners[0];
  const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
  const double r1 = r.dot(e1), r2 = r.dot(e2);
  const double det = d11 * d22 - d12 * d12;
  const double u = (d22 * r1 - d12 * r2) / det, w = (d11 * r2 - d12 * r1) / det;
  return {1.0 - u - w, u, w};
}

}  // namespace

bool nodeHitsTriangle(const SweptNode& node, const SweptTriangle& triangle, double skin,
                      double shallow, NodeTriangleHit* hit) {
  Eigen::Vector3d normal;
  double end_distance = 0.0;
  if (!planeDistance(triangle.end, node.end, normal, end_distance) || !(end_distance < skin)) {
    return false;
  }
  const Eigen::Vector3d weights = barycentric(triangle.end, node.end - end_distance * normal);
  if (!(weights.minCoeff() >= -slackFor(triangle.end, std::max(-end_distance, 0.0)))) return false;
  Eigen::Vector3d start_normal;
  double start_distance = 0.0;
  hit->crossed = end_distance < 0.0 &&
                 planeDistance(triangle.start, node.start, start_normal, start_distance) &&
                 start_distance >= -skin;
  // Deep behind the plane from the start: inside the body, not through this triangle.
  if (!hit->crossed && -end_distance > shallow) return false;
  hit->depth = -end_distance;
  hit->normal = normal;
  hit->weights = weights.cwiseMax(0.0) / weights.cwiseMax(0.0).sum();
  return true;
}

}  // namespace deformable_sim::core
