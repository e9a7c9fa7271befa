#include "deformable_sim/perf/scan_blob.h"

#include <cmath>
#include <random>

#include "deformable_sim/core/geometry/uv_sphere.h"

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

}  // namespace

core::TriangleMesh makeScanBlob(int rings, int segments) {
  std::mt19937 random(2018);
  std::uniform_real_distribution<double> rough(-kRoughness, kRoughness);
  // Rough everywhere but at the poles.
  return core::uvSphere(rings, segments, [&](double polar, double azimuth) {
    const bool pole = polar == 0.0 || polar == M_PI;
    return lobedRadius(polar, azimuth) * (pole ? 1.0 : 1.0 + rough(random));
  });
}

}  // namespace deformable_sim::perf
