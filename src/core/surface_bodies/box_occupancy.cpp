#include "deformable_sim/core/surface_bodies/box_occupancy.h"

#include <Eigen/Geometry>
#include <cmath>

namespace deformable_sim::core {

bool triangleMayCrossCube(const TriangleMesh& surface, int t, const Eigen::Vector3d& min,
                          double size, double margin) {
  const Eigen::Vector3i& tri = surface.triangles[t];
  const Eigen::Vector3d& a = surface.vertices[tri[0]];
  const Eigen::Vector3d& b = surface.vertices[tri[1]];
  const Eigen::Vector3d& c = surface.vertices[tri[2]];
  const Eigen::Vector3d low = min.array() - margin, high = min.array() + size + margin;
  const Eigen::Vector3d tri_low = a.cwiseMin(b).cwiseMin(c), tri_high = a.cwiseMax(b).cwiseMax(c);
  if ((tri_high.array() < low.array()).any() || (tri_low.array() > high.array()).any()) {
    return false;
  }
  // The plane through the triangle meets the cube when the centre is within the cube's
  // half-extent along the normal.
  const Eigen::Vector3d normal = (b - a).cross(c - a);
  const Eigen::Vector3d centre = min.array() + 0.5 * size;
  const double reach = (0.5 * size + margin) * normal.cwiseAbs().sum();
  return std::abs(normal.dot(centre - a)) <= reach;
}

double occupiedFraction(const TriangleMesh& surface, const InsideTest& inside,
                        const std::vector<int>& candidates, const Eigen::Vector3d& min, double size,
                        int levels) {
  if (candidates.empty() || levels == 0) {
    return inside(min.array() + 0.5 * size) ? 1.0 : 0.0;
  }
  double sum = 0.0;
  for (double f : octantFractions(surface, inside, candidates, min, size, levels)) sum += f;
  return sum / 8.0;
}

std::array<double, 8> octantFractions(const TriangleMesh& surface, const InsideTest& inside,
                                      const std::vector<int>& candidates,
                                      const Eigen::Vector3d& min, double size, int levels) {
  const double half = 0.5 * size;
  // A triangle lying on a face between two parts crosses both; the margin keeps it in both lists.
  const double margin = 1e-9 * size;
  std::vector<int> crossing;
  crossing.reserve(candidates.size());
  std::array<double, 8> fractions;
  for (int octant = 0; octant < 8; ++octant) {
    const Eigen::Vector3d part_min =
        min + half * Eigen::Vector3d(octant & 1, octant >> 1 & 1, octant >> 2 & 1);
    crossing.clear();
    for (int t : candidates) {
      if (triangleMayCrossCube(surface, t, part_min, half, margin)) crossing.push_back(t);
    }
    fractions[octant] = occupiedFraction(surface, inside, crossing, part_min, half, levels - 1);
  }
  return fractions;
}

}  // namespace deformable_sim::core
