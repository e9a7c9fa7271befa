// Closed triangle surfaces for the voxelization tests, counter-clockwise seen from outside.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <string>

#include "deformable_sim/core/triangle_mesh.h"

namespace deformable_sim::test {

/// Adds the quad a b c d (counter-clockwise seen from outside) as two triangles.
inline void addQuad(core::TriangleMesh& mesh, int a, int b, int c, int d) {
  mesh.triangles.emplace_back(a, b, c);
  mesh.triangles.emplace_back(a, c, d);
}

/// A UV sphere of radius r about `centre`, its poles merged into single vertices.
inline core::TriangleMesh sphereSurface(double radius, const Eigen::Vector3d& centre, int rings,
                                        int segments) {
  core::TriangleMesh mesh;
  mesh.vertices.push_back(centre - radius * Eigen::Vector3d::UnitZ());  // south pole
  for (int r = 1; r < rings; ++r) {
    const double polar = M_PI * (1.0 - static_cast<double>(r) / rings);  // from the south
    for (int s = 0; s < segments; ++s) {
      const double azimuth = 2.0 * M_PI * s / segments;
      mesh.vertices.push_back(centre + radius * Eigen::Vector3d(std::sin(polar) * std::cos(azimuth),
                                                                std::sin(polar) * std::sin(azimuth),
                                                                std::cos(polar)));
    }
  }
  mesh.vertices.push_back(centre + radius * Eigen::Vector3d::UnitZ());  // north pole
  const int north = static_cast<int>(mesh.vertices.size()) - 1;
  auto ring = [&](int r, int s) { return 1 + (r - 1) * segments + s % segments; };
  for (int s = 0; s < segments; ++s) {
    mesh.triangles.emplace_back(0, ring(1, s + 1), ring(1, s));
    mesh.triangles.emplace_back(north, ring(rings - 1, s), ring(rings - 1, s + 1));
    for (int r = 1; r + 1 < rings; ++r) {
      addQuad(mesh, ring(r, s), ring(r, s + 1), ring(r + 1, s + 1), ring(r + 1, s));
    }
  }
  return mesh;
}

/// A torus about z: tube radius `minor` around the circle of radius `major`.
inline core::TriangleMesh torusSurface(double major, double minor, int around, int tube) {
  core::TriangleMesh mesh;
  for (int i = 0; i < around; ++i) {
    const double u = 2.0 * M_PI * i / around;
    for (int j = 0; j < tube; ++j) {
      const double v = 2.0 * M_PI * j / tube;
      const double rho = major + minor * std::cos(v);
      mesh.vertices.emplace_back(rho * std::cos(u), rho * std::sin(u), minor * std::sin(v));
    }
  }
  auto index = [&](int i, int j) { return (i % around) * tube + j % tube; };
  for (int i = 0; i < around; ++i) {
    for (int j = 0; j < tube; ++j) {
      addQuad(mesh, index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1));
    }
  }
  return mesh;
}

/// The box [min, max] as 12 triangles (core::boxSurface), every point moved by `pose`.
inline core::TriangleMesh boxSurface(
    const Eigen::Vector3d& min, const Eigen::Vector3d& max,
    const Eigen::Isometry3d& pose = Eigen::Isometry3d::Identity()) {
  core::TriangleMesh mesh = core::boxSurface(min, max);
  for (Eigen::Vector3d& v : mesh.vertices) v = pose * v;
  return mesh;
}

/// Writes `mesh` as an ASCII STL (each triangle with its own three vertices, as STL has it).
inline void writeAsciiStl(const core::TriangleMesh& mesh, const std::string& path) {
  std::ofstream out(path);
  out.precision(17);
  out << "solid test\n";
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    const Eigen::Vector3d n = (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).normalized();
    out << "facet normal " << n.x() << " " << n.y() << " " << n.z() << "\nouter loop\n";
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d& v = mesh.vertices[t[c]];
      out << "vertex " << v.x() << " " << v.y() << " " << v.z() << "\n";
    }
    out << "endloop\nendfacet\n";
  }
  out << "endsolid test\n";
}

}  // namespace deformable_sim::test
