// Selecting nodes of a mesh: by the mesh file's node numbers or by a region (box, sphere) that the
// rest position of the node lies in.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "deformable_sim/core/elements/mesh.h"

namespace deformable_sim::core {

struct Box {
  Eigen::Vector3d min = Eigen::Vector3d::Zero();  ///< m
  Eigen::Vector3d max = Eigen::Vector3d::Zero();  ///< m
};

struct Sphere {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  ///< m
  double radius = 0.0;                               ///< m, >= 0
};

struct NodeSelection {
  enum class Kind { kNodes, kBox, kSphere };
  Kind kind = Kind::kNodes;
  std::vector<long> node_numbers;  ///< kNodes: the mesh file's node numbers
  Box box;                         ///< kBox: closed box, min <= max per axis
  Sphere sphere;                   ///< kSphere: closed ball
};

/// Indices (into Mesh::positions) of the selected nodes, ascending, without duplicates. Regions
/// are tested against rest positions. Throws std::invalid_argument for an unknown node number,
/// a box with min > max, a negative or non-finite radius. An empty result is not an error here.
std::vector<int> selectNodes(const Mesh& mesh, const NodeSelection& selection);

/// The same, with regions tested against `positions` (stacked 3n, m): the body as it is now.
std::vector<int> selectNodesAt(const Mesh& mesh, const Eigen::VectorXd& positions,
                               const NodeSelection& selection);

}  // namespace deformable_sim::core
