#include "deformable_sim/core/driver/body_frame_lookup.h"

#include <cstdio>

#include "deformable_sim/core/bodies/rigid_frame.h"

namespace deformable_sim::core {

namespace {

Eigen::Isometry3d pose(const Body& body, const std::vector<int>& nodes = {}) {
  return toIsometry(
      bestFitFrame(body.positions(), body.restPositions(), body.nodalMasses(), nodes));
}

std::string groupNames(const Body& body) {
  std::string names;
  for (const auto& [group, nodes] : body.mesh().groups)
    names += (names.empty() ? "" : ", ") + group;
  return names;
}

std::string metres(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g m", value);
  return text;
}

}  // namespace

BodyFrame findBodyFrame(const BodyList& bodies, const std::string& prefix,
                        const std::string& frame) {
  for (size_t b = 0; b < bodies.size(); ++b) {
    const Body& body = bodies[b];
    const std::string name = prefix + body.name();
    if (frame == name) return {static_cast<int>(b), "", pose(body)};
    if (frame.rfind(name + "/", 0) != 0) continue;
    const std::string group = frame.substr(name.size() + 1);
    const auto found = body.mesh().groups.find(group);
    if (found == body.mesh().groups.end()) {
      const std::string groups = groupNames(body);
      throw CommandError("frame '" + frame + "': body '" + body.name() + "' has no group '" +
                         group + "'" + (groups.empty() ? "" : " (groups: " + groups + ")"));
    }
    return {static_cast<int>(b), group, pose(body, found->second)};
  }
  return {};
}

std::vector<std::pair<std::string, Eigen::Isometry3d>> allBodyFrames(const BodyList& bodies,
                                                                     const std::string& prefix) {
  std::vector<std::pair<std::string, Eigen::Isometry3d>> frames;
  for (const Body& body : bodies) {
    frames.emplace_back(prefix + body.name(), pose(body));
    for (const auto& [group, nodes] : body.mesh().groups) {
      frames.emplace_back(prefix + body.name() + "/" + group, pose(body, nodes));
    }
  }
  return frames;
}

std::string bodyFrameNames(const BodyList& bodies, const std::string& prefix) {
  std::string names;
  for (const Body& body : bodies) names += (names.empty() ? "" : ", ") + prefix + body.name();
  return names;
}

NearestNode nearestNode(const BodyList& bodies, const Eigen::Vector3d& point) {
  NearestNode nearest;
  for (size_t b = 0; b < bodies.size(); ++b) {
    const Eigen::VectorXd& x = bodies[b].positions();
    for (int i = 0; i < bodies[b].numNodes(); ++i) {
      const double d = (x.segment<3>(3 * i) - point).norm();
      if (d < nearest.distance) nearest = {static_cast<int>(b), i, d};
    }
  }
  return nearest;
}

WrenchCommand wrenchNearPoint(const Simulation& simulation, const std::string& frame,
                              const Eigen::Vector3d& point, const Eigen::Vector3d& force,
                              const Eigen::Vector3d& torque) {
  const NearestNode nearest = nearestNode(simulation.bodies(), point);
  if (nearest.body < 0) throw CommandError("frame '" + frame + "': there is no body");
  const Body& body = simulation.bodies()[nearest.body];
  const double radius = simulation.wrenchRadius(nearest.body);
  if (!(nearest.distance <= radius)) {
    throw CommandError("frame '" + frame + "' is " + metres(nearest.distance) +
                       " from the nearest body, '" + body.name() + "', beyond its wrench_radius " +
                       metres(radius) +
                       ": move the frame onto the body, or raise the body's wrench_radius");
  }
  WrenchCommand command;
  command.source = frame;
  command.body = body.name();
  command.force = force;
  command.torque = torque;
  command.point = point;
  command.nodes.sphere = Sphere{point, radius};
  return command;
}

WrenchCommand wrenchInFrame(const Simulation& simulation, const std::string& frame,
                            const BodyFrame& target, const Eigen::Vector3d& force,
                            const Eigen::Vector3d& torque) {
  const Eigen::Matrix3d rotation = target.pose.linear();
  const Eigen::Vector3d origin = target.pose.translation();
  if (target.body < 0) {
    return wrenchNearPoint(simulation, frame, origin, rotation * force, rotation * torque);
  }
  WrenchCommand command;
  command.source = frame;
  command.body = simulation.bodies()[target.body].name();
  command.nodes.group = target.group;
  command.nodes.whole_body = target.group.empty();
  command.force = rotation * force;
  command.torque = rotation * torque;
  command.point = origin;
  return command;
}

}  // namespace deformable_sim::core
