#include "deformable_sim/core/session/commands.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "deformable_sim/core/bodies/wrench.h"

namespace deformable_sim::core {

std::string vectorText(const Eigen::Vector3d& v) {
  char text[96];
  std::snprintf(text, sizeof text, "(%g, %g, %g)", v.x(), v.y(), v.z());
  return text;
}

Wrench seenFrom(const Wrench& wrench, const Eigen::Isometry3d& frame) {
  const Eigen::Matrix3d to_frame = frame.linear().transpose();
  Wrench seen;  // about the frame's origin: zero in the frame's own coordinates
  seen.force = to_frame * wrench.force;
  seen.torque =
      to_frame * (wrench.torque + (wrench.point - frame.translation()).cross(wrench.force));
  return seen;
}

CommandProcessor::CommandProcessor(Simulation& simulation, CommandLimits limits)
    : simulation_(simulation), limits_(limits) {
  for (const Body& body : simulation_.bodies()) base_forces_.push_back(body.externalForces());
}

int CommandProcessor::findBody(const std::string& name, const NodeTarget& nodes) const {
  const BodyList& bodies = simulation_.bodies();
  if (!name.empty()) {
    const int index = simulation_.bodyIndex(name);
    if (index >= 0) return index;
    std::string known;
    for (const Body& b : bodies) known += (known.empty() ? "'" : ", '") + b.name() + "'";
    throw CommandError("unknown body '" + name + "' (bodies: " + known + ")");
  }
  if (bodies.size() == 1) return 0;
  if (!nodes.sphere) throw CommandError("no body named and the scene has several bodies");
  if (!nodes.sphere->center.allFinite() || !nodes.region_pose.matrix().allFinite()) {
    throw CommandError("the sphere's centre has a non-finite coordinate");
  }
  // The body with a node nearest to the centre, in the world (the sphere is in region_pose, as
  // resolving its nodes takes it).
  const Eigen::Vector3d center = nodes.region_pose * nodes.sphere->center;
  int best = -1;
  double best_distance = std::numeric_limits<double>::infinity();
  for (size_t b = 0; b < bodies.size(); ++b) {
    const Eigen::VectorXd& x = bodies[b].positions();
    for (int i = 0; i < bodies[b].numNodes(); ++i) {
      const double d = (x.segment<3>(3 * i) - center).norm();
      if (d < best_distance) best_distance = d, best = static_cast<int>(b);
    }
  }
  // Every distance overflowed (a centre near the largest double).
  if (best < 0) throw CommandError("the sphere's centre is too far from every body");
  return best;
}

namespace {

std::vector<int> groupMembers(const Body& body, const std::string& group_name) {
  const auto group = body.mesh().groups.find(group_name);
  if (group == body.mesh().groups.end()) {
    std::string known;
    for (const auto& [name, members] : body.mesh().groups)
      known += (known.empty() ? "" : ", ") + name;
    throw CommandError("body '" + body.name() + "' has no group '" + group_name + "'" +
                       (known.empty() ? " (it has none)" : " (groups: " + known + ")"));
  }
  return group->second;
}

// The nodes within nodes.shape_margin of any of nodes.shapes, ascending.
std::vector<int> nodesNearShapes(const Body& body, const NodeTarget& nodes) {
  if (!(nodes.shape_margin >= 0.0) || !std::isfinite(nodes.shape_margin)) {
    throw CommandError("the margin around the shapes must be finite and >= 0 m");
  }
  std::vector<int> selected;
  for (const PlacedShape& placed : nodes.shapes) {
    const Eigen::Isometry3d to_shape = placed.pose.inverse();
    for (int i = 0; i < body.numNodes(); ++i) {
      const Eigen::Vector3d p = body.positions().segment<3>(3 * i);
      if (signedDistance(placed.shape, to_shape * p) <= nodes.shape_margin) selected.push_back(i);
    }
  }
  std::sort(selected.begin(), selected.end());
  selected.erase(std::unique(selected.begin(), selected.end()), selected.end());
  if (selected.empty()) {
    throw CommandError("body '" + body.name() + "': no node within " +
                       std::to_string(nodes.shape_margin) + " m of '" + nodes.shapes[0].name + "'");
  }
  return selected;
}

// The nodes named by number, or inside the box or sphere (in nodes.region_pose).
std::vector<int> nodesInRegion(const Body& body, const NodeTarget& nodes) {
  NodeSelection selection;
  if (!nodes.node_numbers.empty()) {
    selection.kind = NodeSelection::Kind::kNodes;
    selection.node_numbers = nodes.node_numbers;
  } else if (nodes.box) {
    selection.kind = NodeSelection::Kind::kBox;
    selection.box = *nodes.box;
  } else {
    selection.kind = NodeSelection::Kind::kSphere;
    selection.sphere = *nodes.sphere;
  }
  std::vector<int> selected;
  try {
    if (!nodes.region_pose.matrix().allFinite())
      throw CommandError("the region's frame is not finite");
    if (nodes.region_pose.matrix().isIdentity(0.0)) {
      selected = selectNodesAt(body.mesh(), body.positions(), selection);
    } else {
      // Test the nodes in the region's own frame.
      const Eigen::Isometry3d to_region = nodes.region_pose.inverse();
      Eigen::VectorXd local(body.positions().size());
      for (int i = 0; i < body.numNodes(); ++i) {
        local.segment<3>(3 * i) = to_region * Eigen::Vector3d(body.positions().segment<3>(3 * i));
      }
      selected = selectNodesAt(body.mesh(), local, selection);
    }
  } catch (const std::invalid_argument& e) {
    throw CommandError("body '" + body.name() + "': " + e.what());
  }
  if (selected.empty()) {
    throw CommandError("body '" + body.name() + "': the " +
                       std::string(nodes.box ? "box" : "sphere") + " contains no node");
  }
  return selected;
}

void addNodalForces(const ActiveWrench& wrench, Eigen::VectorXd& forces) {
  for (size_t k = 0; k < wrench.nodes.size(); ++k)
    forces.segment<3>(3 * wrench.nodes[k]) += wrench.forces[k];
}

void checkWrenchValues(const WrenchCommand& command) {
  if (!command.force.allFinite() || !command.torque.allFinite() ||
      (command.point && !command.point->allFinite())) {
    throw CommandError("wrench from '" + command.source + "' has a NaN or infinite value");
  }
}

void checkWrenchBounds(const WrenchCommand& command, const Body& body,
                       const CommandLimits& limits) {
  const WrenchBounds bounds = wrenchBounds(body, limits);
  if (command.force.norm() > bounds.force || command.torque.norm() > bounds.torque) {
    throw CommandError("wrench from '" + command.source + "' exceeds the limits of body '" +
                       body.name() + "' (|force| " + std::to_string(command.force.norm()) +
                       " N of at most " + std::to_string(bounds.force) + ", |torque| " +
                       std::to_string(command.torque.norm()) + " N m of at most " +
                       std::to_string(bounds.torque) + ")");
  }
}

// Shares the command's wrench among active.nodes (set) of `body` by their masses, about the
// command's point or else their centre of mass.
void distributeOverNodes(const Body& body, const WrenchCommand& command, ActiveWrench& active) {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> weights;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double total = 0.0;
  for (int i : active.nodes) {
    points.emplace_back(body.positions().segment<3>(3 * i));
    weights.push_back(body.nodalMasses()[i]);
    centroid += weights.back() * points.back();
    total += weights.back();
  }
  active.force = command.force;
  active.torque = command.torque;
  active.point = command.point.value_or(centroid / total);
  try {
    distributeWrench(points, weights, command.force, command.torque, active.point, active.forces);
  } catch (const std::invalid_argument& e) {
    throw CommandError("wrench from '" + command.source + "' on body '" + body.name() +
                       "': " + e.what());
  }
}

}  // namespace

std::vector<int> CommandProcessor::resolve(const Body& body, const NodeTarget& nodes) const {
  const int kinds = (nodes.node_numbers.empty() ? 0 : 1) + (nodes.group.empty() ? 0 : 1) +
                    (nodes.box ? 1 : 0) + (nodes.sphere ? 1 : 0) + (nodes.shapes.empty() ? 0 : 1);
  if (kinds == 0 && nodes.whole_body) {
    std::vector<int> all(body.numNodes());
    for (int i = 0; i < body.numNodes(); ++i) all[i] = i;
    return all;
  }
  if (kinds != 1) {
    throw CommandError("give exactly one of: node ids, a group, a box, a sphere, shapes (got " +
                       std::to_string(kinds) + ")");
  }
  if (!nodes.group.empty()) return groupMembers(body, nodes.group);
  if (!nodes.shapes.empty()) return nodesNearShapes(body, nodes);
  return nodesInRegion(body, nodes);
}

int CommandProcessor::apply(const WrenchCommand& command) {
  checkWrenchValues(command);
  if (command.force.isZero(0.0) && command.torque.isZero(0.0)) {
    // A zero wrench clears its source; nothing to resolve (the target may be gone).
    if (!clearWrench(command.source)) {
      // Nothing to clear: it must still name nodes a wrench could act on, so that unknown
      // bodies, nodes and groups are refused whatever the wrench.
      resolve(simulation_.bodies()[findBody(command.body, command.nodes)], command.nodes);
    }
    return 0;
  }
  const int b = findBody(command.body, command.nodes);
  const Body& body = simulation_.bodies()[b];
  checkWrenchBounds(command, body, limits_);
  ActiveWrench active;
  active.body = b;
  active.nodes = resolve(body, command.nodes);
  distributeOverNodes(body, command, active);
  // A wrench about a point far away, or many large ones on one node, can overflow: refuse it
  // before it reaches the body.
  Eigen::VectorXd applied = base_forces_[b];
  addWrenchForces(b, &command.source, applied);
  addNodalForces(active, applied);
  if (!applied.allFinite()) {
    throw CommandError("wrench from '" + command.source + "' on body '" + body.name() +
                       "': its nodal forces overflow (a point of application too far away?)");
  }
  const auto previous = wrenches_.find(command.source);
  const int previous_body = previous == wrenches_.end() ? -1 : previous->second.body;
  wrenches_[command.source] = std::move(active);
  if (previous_body >= 0 && previous_body != b) updateExternalForces(previous_body);
  updateExternalForces(b);
  return static_cast<int>(wrenches_[command.source].nodes.size());
}

int CommandProcessor::apply(const FixCommand& command) {
  const int b = findBody(command.body, command.nodes);
  Body& body = simulation_.bodies()[b];
  const std::vector<int> nodes = resolve(body, command.nodes);
  for (int i : nodes) {
    if (const std::string* grasp = graspOf(b, i)) {
      throw CommandError("node " + std::to_string(body.mesh().node_numbers[i]) +
                         " is held by grasp '" + *grasp + "': release the grasp instead");
    }
  }
  if (!command.fix) {
    if (!command.targets.empty() || command.translation) {
      throw CommandError("a release takes no targets or translation");
    }
    body.releaseNodes(nodes);
    return static_cast<int>(nodes.size());
  }
  // Targets in the order the user gave node numbers (resolve() sorts them).
  std::vector<int> order = nodes;
  if (!command.nodes.node_numbers.empty()) {
    order = nodeIndices(body.mesh(), command.nodes.node_numbers);
  }
  if (!command.targets.empty() && command.targets.size() != order.size()) {
    throw CommandError("body '" + body.name() + "': " + std::to_string(command.targets.size()) +
                       " targets for " + std::to_string(order.size()) + " nodes");
  }
  if (!command.targets.empty() && command.translation) {
    throw CommandError("give targets or a translation, not both");
  }
  if (command.translation && !command.translation->allFinite()) {
    throw CommandError("translation has a NaN or infinite value");
  }
  std::vector<Eigen::Vector3d> targets(order.size());
  for (size_t k = 0; k < order.size(); ++k) {
    const Eigen::Vector3d here = body.positions().segment<3>(3 * order[k]);
    targets[k] = !command.targets.empty() ? command.targets[k]
                 : command.translation    ? Eigen::Vector3d(here + *command.translation)
                                          : here;
    if (!targets[k].allFinite()) {
      throw CommandError("target of node " + std::to_string(body.mesh().node_numbers[order[k]]) +
                         " has a NaN or infinite value");
    }
    if ((targets[k] - here).norm() > limits_.max_target_distance) {
      throw CommandError("target " + vectorText(targets[k]) + " of node " +
                         std::to_string(body.mesh().node_numbers[order[k]]) + " is more than " +
                         std::to_string(limits_.max_target_distance) + " m from the node");
    }
  }
  body.setNodeTargets(order, targets);
  return static_cast<int>(order.size());
}

bool CommandProcessor::clearWrench(const std::string& source) {
  const auto found = wrenches_.find(source);
  if (found == wrenches_.end()) return false;
  const int body = found->second.body;
  wrenches_.erase(found);
  updateExternalForces(body);
  return true;
}

void CommandProcessor::addWrenchForces(int b, const std::string* except,
                                       Eigen::VectorXd& forces) const {
  for (const auto& [source, wrench] : wrenches_) {
    if (wrench.body != b || (except && source == *except)) continue;
    addNodalForces(wrench, forces);
  }
}

void CommandProcessor::updateExternalForces(int b) {
  Eigen::VectorXd& f = simulation_.bodies()[b].externalForces();
  f = base_forces_[b];
  addWrenchForces(b, nullptr, f);
}

}  // namespace deformable_sim::core
