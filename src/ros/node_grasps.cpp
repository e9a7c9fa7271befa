#include "deformable_sim/ros/node_grasps.h"

#include <ros/names.h>

#include "deformable_sim/ros/conversions.h"

namespace deformable_sim::ros_layer {

uint32_t NodeGrasps::handle(const core::Session& session, const Grasp& message) {
  if (message.action == Grasp::RELEASE) {
    const auto found = session.commands().grasps().find(message.name);
    if (found == session.commands().grasps().end()) {
      throw core::CommandError("no grasp named '" + message.name + "'");
    }
    const auto nodes = static_cast<uint32_t>(found->second.nodes.size());
    apply_(core::ReleaseGraspCommand{message.name});
    follower_.forget(message.name);
    wrench_pubs_.erase(message.name);  // its topic goes with it: names do not pile up
    return nodes;
  }
  if (message.action != Grasp::ATTACH) {
    throw core::CommandError("action " + std::to_string(message.action) +
                             " is neither ATTACH (0) nor RELEASE (1)");
  }
  // The name becomes a topic (~grasps/<name>/wrench) and a tf frame (<name>/object).
  std::string invalid;
  if (message.name.empty() || !ros::names::validate("grasps/" + message.name, invalid)) {
    throw core::CommandError("grasp '" + message.name +
                             "': not a valid ROS name (letters, digits, _ and /): " + invalid);
  }
  const auto nodes = static_cast<uint32_t>(apply_(attachCommand(session.simulation(), message)));
  follower_.follow(message.name, withoutLeadingSlash(message.header.frame_id));
  if (wrench_pubs_.count(message.name) == 0) {
    wrench_pubs_[message.name] =
        node_.advertise<geometry_msgs::WrenchStamped>("grasps/" + message.name + "/wrench", 10);
  }
  return nodes;
}

core::GraspCommand NodeGrasps::attachCommand(const core::Simulation& simulation,
                                             const Grasp& message) {
  const std::string name = "grasp '" + message.name + "': ";
  const std::string frame = withoutLeadingSlash(message.header.frame_id);
  if (frame.empty()) throw core::CommandError(name + "header.frame_id is empty: name the frame");
  core::BodyFrame target;
  try {
    target = frames_.resolve(simulation, frame);
  } catch (const core::CommandError& e) {
    throw core::CommandError(name + e.what());
  }
  if (target.body >= 0 || frame == frames_.worldFrame()) {
    throw core::CommandError(name + "'" + frame +
                             "' is not a tf frame that can hold a body (it is the world or one "
                             "of this node's frames)");
  }
  core::GraspCommand command;
  command.name = message.name;
  command.body = message.body;
  command.frame = target.pose;
  if (message.region == Grasp::REGION_LINK) {
    command.nodes = linkRegion(message, frame);
  } else if (!setRegion(message, target.pose, command.nodes)) {
    throw core::CommandError(name + "region " + std::to_string(message.region) +
                             " is not REGION_BOX, REGION_SPHERE or REGION_LINK");
  }
  return command;
}

core::NodeTarget NodeGrasps::linkRegion(const Grasp& message, const std::string& frame) {
  const std::string link = message.link.empty() ? frame : message.link;
  const std::string name = "grasp '" + message.name + "': link '" + link + "': ";
  core::NodeTarget region;
  std::string error;
  const std::optional<Eigen::Isometry3d> pose = frames_.lookup(link, &error);
  if (!pose) throw core::CommandError(name + error);
  try {
    for (core::PlacedShape shape : links_.shapes(link)) {
      shape.pose = *pose * shape.pose;
      region.shapes.push_back(shape);
    }
  } catch (const core::CommandError& e) {
    throw core::CommandError(name + e.what());
  }
  region.shape_margin = message.margin;
  return region;
}

void NodeGrasps::planMoves(const core::CommandProcessor& commands) {
  const auto pose = [this](const std::string& frame) { return frames_.lookup(frame, nullptr); };
  for (const std::string& grasp : follower_.plan(commands, pose)) {
    ROS_WARN_THROTTLE(1.0, "grasp '%s': frame '%s' is not in tf now; holding its last pose",
                      grasp.c_str(), follower_.frames().at(grasp).c_str());
  }
}

void NodeGrasps::move(int s, int steps) {
  for (const core::MoveGraspCommand& move : follower_.moves(s, steps)) {
    try {
      apply_(move);
    } catch (const core::CommandError& e) {
      ROS_WARN_THROTTLE(1.0, "%s; holding its last pose", e.what());
    }
  }
}

void NodeGrasps::publish(const core::Session& session, const ros::Time& stamp,
                         tf2_ros::TransformBroadcaster* broadcaster) {
  std::vector<geometry_msgs::TransformStamped> objects;
  for (const auto& [name, frame] : follower_.frames()) {
    const core::CommandProcessor& commands = session.commands();
    wrench_pubs_.at(name).publish(
        toMessage(commands.graspReaction(name), frame, commands.grasps().at(name).frame, stamp));
    geometry_msgs::TransformStamped object;
    object.header.stamp = stamp;
    object.header.frame_id = frame;
    object.child_frame_id = frames_.prefix() + name + "/object";
    object.transform = toTransform(commands.objectInGrasp(name));
    objects.push_back(object);
  }
  if (broadcaster && !objects.empty()) broadcaster->sendTransform(objects);
}

void NodeGrasps::clear() {
  follower_.clear();
  wrench_pubs_.clear();
}

}  // namespace deformable_sim::ros_layer
