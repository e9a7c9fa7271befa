#include "deformable_sim/core/geometry/uv_sphere.h"

#include <cmath>

namespace deformable_sim::core {

TriangleMesh uvSphere(int rings, int segments, const SphereRadius& radius) {
  TriangleMesh mesh;
  mesh.vertices.push_back(-radius(M_PI, 0.0) * Eigen::Vector3d::UnitZ());  // south pole
  for (int r = 1; r < rings; ++r) {
    const double polar = M_PI * (1.0 - static_cast<double>(r) / rings);
    for (int s = 0; s < segments; ++s) {
      const double azimuth = 2.0 * M_PI * s / segments;
      const Eigen::Vector3d direction(std::sin(polar) * std::cos(azimuth),
                                      std::sin(polar) * std::sin(azimuth), std::cos(polar));
      mesh.vertices.push_back(radius(polar, azimuth) * direction);
    }
  }
  mesh.vertices.push_back(radius(0.0, 0.0) * Eigen::Vector3d::UnitZ());  // north pole
  const int north = static_cast<int>(mesh.vertices.size()) - 1;
  auto ring = [&](int r, int s) { return 1 + (r - 1) * segments + s % segments; };
  for (int s = 0; s < segments; ++s) {
    mesh.triangles.emplace_back(0, ring(1, s + 1), ring(1, s));
    mesh.triangles.emplace_back(north, ring(rings - 1, s), ring(rings - 1, s + 1));
    for (int r = 1; r + 1 < rings; ++r) {
      mesh.triangles.emplace_back(ring(r, s), ring(r, s + 1), ring(r + 1, s + 1));
      mesh.triangles.emplace_back(ring(r, s), ring(r + 1, s + 1), ring(r + 1, s));
    }
  }
  return mesh;
}

}  // namespace deformable_sim::core
