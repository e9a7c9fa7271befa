#include "deformable_sim/ros/conversions.h"

namespace deformable_sim::ros_layer {

geometry_msgs::WrenchStamped toMessage(const core::Wrench& wrench, const std::string& frame_id,
                                       const Eigen::Isometry3d& frame, const ros::Time& stamp) {
  const core::Wrench seen = core::seenFrom(wrench, frame);
  geometry_msgs::WrenchStamped m;
  m.header.stamp = stamp;
  m.header.frame_id = frame_id;
  m.wrench.force = toVector3(seen.force);
  m.wrench.torque = toVector3(seen.torque);
  return m;
}

core::WrenchCommand toCommand(const NodeWrench& message, const Eigen::Isometry3d& frame_in_world) {
  core::WrenchCommand command;
  command.body = message.body;
  command.nodes.node_numbers.assign(message.nodes.begin(), message.nodes.end());
  command.nodes.group = message.group;
  command.force = frame_in_world.linear() * toEigen(message.wrench.force);
  command.torque = frame_in_world.linear() * toEigen(message.wrench.torque);
  // One source per body and node set: a later message for the same nodes replaces this one.
  command.source = "node_wrench:" + message.body + ":";
  if (!message.group.empty()) {
    command.source += "group " + message.group;
  } else {
    for (int64_t n : message.nodes) command.source += std::to_string(n) + " ";
  }
  return command;
}

core::FixCommand toCommand(const FixedNodes& message, const Eigen::Isometry3d& frame_in_world) {
  core::FixCommand command;
  command.body = message.body;
  if (message.action != FixedNodes::FIX && message.action != FixedNodes::RELEASE) {
    throw core::CommandError("action " + std::to_string(message.action) +
                             " is neither FIX (0) nor RELEASE (1)");
  }
  command.fix = message.action == FixedNodes::FIX;
  command.nodes.node_numbers.assign(message.nodes.begin(), message.nodes.end());
  command.nodes.group = message.group;
  if (message.region != FixedNodes::REGION_NONE &&
      !setRegion(message, frame_in_world, command.nodes)) {
    throw core::CommandError("region " + std::to_string(message.region) +
                             " is not REGION_NONE, REGION_BOX or REGION_SPHERE");
  }
  for (const geometry_msgs::Point& p : message.targets) {
    command.targets.push_back(frame_in_world * toEigen(p));
  }
  const Eigen::Vector3d translation = toEigen(message.translation);
  if (!translation.isZero(0.0) || !translation.allFinite()) {
    command.translation = frame_in_world.linear() * translation;
  }
  return command;
}

void fillState(const core::Body& body, BodyState& message) {
  const int n = body.numNodes();
  message.body = body.name();
  message.node_ids.assign(body.mesh().node_numbers.begin(), body.mesh().node_numbers.end());
  message.positions.resize(n);
  message.velocities.resize(n);
  for (int i = 0; i < n; ++i) {
    message.positions[i] = toPoint(body.positions().segment<3>(3 * i));
    message.velocities[i] = toVector3(body.velocities().segment<3>(3 * i));
  }
}

}  // namespace deformable_sim::ros_layer
