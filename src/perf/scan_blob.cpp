#include "deformable_sim/perf/scan_blob.h"

#include <cmath>
#include <random>

namespace deformable_sim::perf {

namespace {

constexpr double kRadius = 0.1;      // m
constexpr double kRoughness = 3e-3;  // of the radius

// The blob's radius along the direction of polar angle `polar` (from +z) and `azimuth`: three
// lobes of different frequency, so that the surface is neither convex nor symmetric.
double lobedRadius(double polar, double azimuth) {
  const double lobes = 0.10 * std::sin(3.0 * azimuth) * std::sin(polar) +
                       0.06 * std::cos(5.0 * polar + 0.7) +
                       0.04 * std::sin(7.0 * azimuth + 2.0 * polar);
  return kRadius * (1.0 + lobes);
}

Eigen::Vector3d direction(double polar, double azimuth) {
  return {std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth),
          std::cos(polar)};
}

}  // namespace

core::TriangleMesh makeScanBlob(int rings, int segments) {
  std::mt19937 random(2018);
  std::uniform_real_distribution<double> rough(-kRoughness, kRoughness);
  core::TriangleMesh mesh;
  mesh.vertices.push_back(lobedRadius(M_PI, 0.0) * direction(M_PI, 0.0));  // south pole
  for (int r = 1; r < rings; ++r) {
    const double polar = M_PI * (1.0 - static_cast<double>(r) / rings);
    for (int s = 0; s < segments; ++s) {
      const double azimuth = 2.0 * M_PI * s / segments;
      const double radius = lobedRadius(polar, azimuth) * (1.0 + rough(random));
      mesh.vertices.push_back(radius * direction(polar, azimuth));
    }
  }
  mesh.vertices.push_back(lobedRadius(0.0, 0.0) * direction(0.0, 0.0));  // north pole
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

}  // namespace deformable_sim::perf
