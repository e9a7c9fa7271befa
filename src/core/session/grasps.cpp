// The grasp part of CommandProcessor: nodes attached to a moving frame, and what they push with.
#include <Eigen/Geometry>

#include "deformable_sim/core/bodies/rigid_frame.h"
#include "deformable_sim/core/session/commands.h"

namespace deformable_sim::core {

const std::string* CommandProcessor::graspOf(int body, int node) const {
  for (const auto& [name, grasp] : grasps_) {
    if (grasp.body != body) continue;
    for (int i : grasp.nodes) {
      if (i == node) return &name;
    }
  }
  return nullptr;
}

int CommandProcessor::apply(const GraspCommand& command) {
  if (command.name.empty() || command.name.find('/') != std::string::npos) {
    throw CommandError("grasp name '" + command.name + "' must be non-empty, without '/'");
  }
  if (!command.frame.matrix().allFinite()) {
    throw CommandError("grasp '" + command.name + "': the frame's pose is not finite");
  }
  const int b = findBody(command.body, command.nodes);
  Body& body = simulation_.bodies()[b];
  std::vector<int> nodes;
  try {
    nodes = resolve(body, command.nodes);
  } catch (const CommandError& e) {
    throw CommandError("grasp '" + command.name + "': " + e.what());
  }
  const auto previous = grasps_.find(command.name);
  for (int i : nodes) {
    const std::string* holder = graspOf(b, i);
    const bool own = holder && *holder == command.name;
    if ((holder && !own) || (!holder && body.isConstrained(i))) {
      throw CommandError("grasp '" + command.name + "': node " +
                         std::to_string(body.mesh().node_numbers[i]) + " is already " +
                         (holder ? "held by grasp '" + *holder + "'" : std::string("fixed")));
    }
  }
  if (previous != grasps_.end()) releaseGrasp(command.name);
  ActiveGrasp grasp;
  grasp.body = b;
  grasp.nodes = nodes;
  grasp.frame = command.frame;
  const Eigen::Isometry3d to_frame = command.frame.inverse();
  std::vector<Eigen::Vector3d> here;
  for (int i : nodes) {
    here.emplace_back(body.positions().segment<3>(3 * i));
    grasp.local.push_back(to_frame * here.back());
  }
  body.setNodeTargets(nodes, here);
  grasp.targets = std::move(here);
  grasps_[command.name] = std::move(grasp);
  return static_cast<int>(nodes.size());
}

bool CommandProcessor::releaseGrasp(const std::string& name) {
  const auto found = grasps_.find(name);
  if (found == grasps_.end()) return false;
  simulation_.bodies()[found->second.body].releaseNodes(found->second.nodes);
  grasps_.erase(found);
  return true;
}

void CommandProcessor::moveGrasp(const std::string& name, const Eigen::Isometry3d& frame) {
  ActiveGrasp& grasp = grasps_.at(name);
  Body& body = simulation_.bodies()[grasp.body];
  // Into the grasp's own buffer: a grasp moves every tick, and allocates nothing doing so.
  for (size_t k = 0; k < grasp.nodes.size(); ++k) {
    const Eigen::Vector3d& target = grasp.targets[k] = frame * grasp.local[k];
    // A frame that jumps across the world (a pose of 1e300 m) would throw the nodes with it.
    const Eigen::Vector3d here = body.positions().segment<3>(3 * grasp.nodes[k]);
    if (!((target - here).norm() <= limits_.max_target_distance)) {
      throw CommandError("grasp '" + name + "': the frame would take node " +
                         std::to_string(body.mesh().node_numbers[grasp.nodes[k]]) + " to " +
                         vectorText(target) + ", more than " +
                         std::to_string(limits_.max_target_distance) + " m from where it is");
    }
  }
  grasp.frame = frame;
  body.setNodeTargets(grasp.nodes, grasp.targets);
}

Wrench CommandProcessor::graspReaction(const std::string& name) const {
  const ActiveGrasp& grasp = grasps_.at(name);
  const Body& body = simulation_.bodies()[grasp.body];
  Wrench wrench;
  wrench.point = grasp.frame.translation();
  for (int i : grasp.nodes) {
    const Eigen::Vector3d r = body.reactionForces().segment<3>(3 * i);
    wrench.force += r;
    wrench.torque += (body.positions().segment<3>(3 * i) - wrench.point).cross(r);
  }
  return wrench;
}

Eigen::Isometry3d CommandProcessor::objectInGrasp(const std::string& name) const {
  const ActiveGrasp& grasp = grasps_.at(name);
  const Body& body = simulation_.bodies()[grasp.body];
  return grasp.frame.inverse() *
         toIsometry(bestFitFrame(body.positions(), body.restPositions(), body.nodalMasses()));
}

Wrench CommandProcessor::fixedReaction(int b, const Eigen::Vector3d& point) const {
  const Body& body = simulation_.bodies()[b];
  std::vector<bool> grasped(body.numNodes(), false);
  for (const auto& [name, grasp] : grasps_) {
    if (grasp.body != b) continue;
    for (int i : grasp.nodes) grasped[i] = true;
  }
  Wrench wrench;
  wrench.point = point;
  for (int i = 0; i < body.numNodes(); ++i) {
    if (!body.isConstrained(i) || grasped[i]) continue;
    const Eigen::Vector3d r = body.reactionForces().segment<3>(3 * i);
    wrench.force += r;
    wrench.torque += (body.positions().segment<3>(3 * i) - point).cross(r);
  }
  return wrench;
}

}  // namespace deformable_sim::core
