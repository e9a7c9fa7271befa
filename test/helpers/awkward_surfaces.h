// Surfaces that a regular grid cuts badly, as real scans do: a shell one cell thick, a box whose
// corner fills one octant of a cell, a thick saddle, a noisy sphere with holes. Closed ones are
// counter-clockwise seen from outside.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "deformable_sim/core/geometry/triangle_mesh.h"
#include "surface_test_helpers.h"

namespace deformable_sim::test {

/// `mesh` with every triangle turned to face the other way (an inner wall of a shell).
inline core::TriangleMesh turnedInsideOut(core::TriangleMesh mesh) {
  for (Eigen::Vector3i& t : mesh.triangles) std::swap(t[1], t[2]);
  return mesh;
}

/// Both surfaces as one (their vertices renumbered).
inline core::TriangleMesh joined(core::TriangleMesh a, const core::TriangleMesh& b) {
  const int offset = static_cast<int>(a.vertices.size());
  a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (const Eigen::Vector3i& t : b.triangles) {
    a.triangles.push_back(t + Eigen::Vector3i::Constant(offset));
  }
  return a;
}

/// A hollow ball: the sphere of radius `outer` with a void of radius `inner` about `centre`.
inline core::TriangleMesh sphericalShell(double outer, double inner, const Eigen::Vector3d& centre,
                                         int rings, int segments) {
  return joined(sphereSurface(outer, centre, rings, segments),
                turnedInsideOut(sphereSurface(inner, centre, rings, segments)));
}

/// A sheet of `thickness` about the saddle z = curvature (x^2 - y^2) over [-half, half]^2, closed
/// by its four sides; `n` quads along each side of each face.
inline core::TriangleMesh thickSaddle(double half, double curvature, double thickness, int n) {
  core::TriangleMesh mesh;
  auto index = [n](int layer, int i, int j) { return layer * (n + 1) * (n + 1) + j * (n + 1) + i; };
  for (int layer = 0; layer < 2; ++layer) {
    const double offset = (layer == 0 ? -0.5 : 0.5) * thickness;
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        const double x = -half + 2.0 * half * i / n, y = -half + 2.0 * half * j / n;
        mesh.vertices.emplace_back(x, y, curvature * (x * x - y * y) + offset);
      }
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      addQuad(mesh, index(1, i, j), index(1, i + 1, j), index(1, i + 1, j + 1), index(1, i, j + 1));
      addQuad(mesh, index(0, i, j), index(0, i, j + 1), index(0, i + 1, j + 1), index(0, i + 1, j));
    }
  }
  for (int k = 0; k < n; ++k) {
    addQuad(mesh, index(0, k, 0), index(0, k + 1, 0), index(1, k + 1, 0), index(1, k, 0));
    addQuad(mesh, index(0, n, k), index(0, n, k + 1), index(1, n, k + 1), index(1, n, k));
    addQuad(mesh, index(0, k + 1, n), index(0, k, n), index(1, k, n), index(1, k + 1, n));
    addQuad(mesh, index(0, 0, k + 1), index(0, 0, k), index(1, 0, k), index(1, 0, k + 1));
  }
  return mesh;
}

/// A sphere as a scanner sees it: every vertex moved along its radius by up to `noise` (m,
/// uniform), and `holes` patches of triangles missing, each the triangles whose first vertex lies
/// within `hole_radius` of a random point on the surface (seeded: the same surface every time).
inline core::TriangleMesh noisySphereWithHoles(double radius, const Eigen::Vector3d& centre,
                                               int rings, double noise, int holes,
                                               double hole_radius, unsigned seed = 11) {
  core::TriangleMesh mesh = sphereSurface(radius, centre, rings, 2 * rings);
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (Eigen::Vector3d& v : mesh.vertices) {
    v = centre + (v - centre) * (1.0 + noise * unit(random) / radius);
  }
  std::vector<Eigen::Vector3d> hole_centres;
  for (int h = 0; h < holes; ++h) {
    const Eigen::Vector3d direction(unit(random), unit(random), unit(random));
    hole_centres.push_back(centre + radius * direction.normalized());
  }
  std::vector<Eigen::Vector3i> kept;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    bool in_hole = false;
    for (const Eigen::Vector3d& c : hole_centres) {
      in_hole = in_hole || (mesh.vertices[t[0]] - c).norm() < hole_radius;
    }
    if (!in_hole) kept.push_back(t);
  }
  mesh.triangles = kept;
  return mesh;
}

}  // namespace deformable_sim::test
