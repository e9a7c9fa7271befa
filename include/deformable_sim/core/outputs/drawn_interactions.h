// What acts on the bodies, as a viewer draws it: the nodes that grasps hold and that are fixed,
// the node groups, and an arrow for every applied wrench. The node's ~markers draw them.
#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "deformable_sim/core/bodies/body_list.h"
#include "deformable_sim/core/session/commands.h"

namespace deformable_sim::core {

/// Where the nodes of one body are, m, world frame.
struct DrawnNodes {
  std::vector<Eigen::Vector3d> grasped;
  std::vector<Eigen::Vector3d> fixed;  ///< constrained and held by no grasp: each node drawn once
  std::vector<std::pair<std::string, std::vector<Eigen::Vector3d>>> groups;  ///< by name
};

struct DrawnArrow {
  Eigen::Vector3d from = Eigen::Vector3d::Zero();
  Eigen::Vector3d to = Eigen::Vector3d::Zero();
};

struct DrawnInteractions {
  std::vector<DrawnNodes> bodies;  ///< one per body
  /// From each wrench's point along its force, `metres_per_newton` long; none for a zero force.
  std::vector<DrawnArrow> wrenches;
};

DrawnInteractions drawnInteractions(const BodyList& bodies, const CommandProcessor& commands,
                                    double metres_per_newton);

}  // namespace deformable_sim::core
