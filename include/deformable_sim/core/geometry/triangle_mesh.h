// A surface made of triangles, as read from an STL, DAE or OBJ file: the geometry of a mesh
// obstacle or of a robot link's collision mesh.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace deformable_sim::core {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;   ///< m, each position once
  std::vector<Eigen::Vector3i> triangles;  ///< vertex indices, counter-clockwise seen from outside
};

/// The box [min, max] as a closed surface of 12 triangles facing outwards; vertex c is the corner
/// with max.x when bit 1 of c is set, max.y for bit 2, max.z for bit 4.
TriangleMesh boxSurface(const Eigen::Vector3d& min, const Eigen::Vector3d& max);

/// The mesh as flat arrays, the way a message carries it: x y z per vertex (appended to
/// `vertices`), three vertex indices per triangle (appended to `triangles`).
void flatten(const TriangleMesh& mesh, std::vector<double>& vertices,
             std::vector<uint32_t>& triangles);
/// The mesh of flat arrays. Throws std::invalid_argument, naming `what`, when an array does not
/// come in threes or a triangle refers to a vertex the arrays do not have.
TriangleMesh unflatten(const std::vector<double>& vertices, const std::vector<uint32_t>& triangles,
                       const std::string& what);

}  // namespace deformable_sim::core
