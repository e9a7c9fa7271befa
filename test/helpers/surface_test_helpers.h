// Closed triangle surfaces for the voxelization tests, counter-clockwise seen from outside.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <string>

#include "deformable_sim/core/geometry/triangle_mesh.h"
#include "deformable_sim/core/geometry/uv_sphere.h"

namespace deformable_sim::test {

/// Adds the quad a b c d (counter-clockwise seen from outside) as two triangles.
inline void addQuad(core::TriangleMesh& mesh, int a, int b, int c, int d) {
  mesh.triangles.emplace_back(a, b, c);
  mesh.triangles.emplace_back(a, c, d);
}

/// A UV sphere of radius r about `centre`, its poles merged into single vertices.
inline core::TriangleMesh sphereSurface(double radius, const Eigen::Vector3d& centre, int rings,
                                        int segments) {
  core::TriangleMesh mesh =
      core::uvSphere(rings, segments, [radius](double, double) { return radius; });
  for (Eigen::Vector3d& v : mesh.vertices) v += centre;
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

/// A cylinder about z from z = 0 to `length`, as CAD writes one: long slivers down its side and
/// each end a fan of `segments` triangles about its centre.
inline core::TriangleMesh cylinderSurface(double radius, double length, int segments) {
  core::TriangleMesh mesh;
  for (int s = 0; s < segments; ++s) {
    const double azimuth = 2.0 * M_PI * s / segments;
    const Eigen::Vector3d rim(radius * std::cos(azimuth), radius * std::sin(azimuth), 0.0);
    mesh.vertices.push_back(rim);
    mesh.vertices.push_back(rim + length * Eigen::Vector3d::UnitZ());
  }
  const int bottom = static_cast<int>(mesh.vertices.size()), top = bottom + 1;
  mesh.vertices.emplace_back(0.0, 0.0, 0.0);
  mesh.vertices.emplace_back(0.0, 0.0, length);
  for (int s = 0; s < segments; ++s) {
    const int low = 2 * s, next = 2 * ((s + 1) % segments);
    addQuad(mesh, low, next, next + 1, low + 1);
    mesh.triangles.emplace_back(bottom, next, low);
    mesh.triangles.emplace_back(top, low + 1, next + 1);
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
