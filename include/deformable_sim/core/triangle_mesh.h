// A surface made of triangles, as read from an STL, DAE or OBJ file: the geometry of a mesh
// obstacle or of a robot link's collision mesh.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace deformable_sim::core {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;   ///< m, each position once
  std::vector<Eigen::Vector3i> triangles;  ///< vertex indices, counter-clockwise seen from outside
};

}  // namespace deformable_sim::core
