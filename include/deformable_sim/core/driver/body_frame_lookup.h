// What a frame name means to a simulation: a body's own frame (<prefix><body>), one of its node
// groups' frames (<prefix><body>/<group>), or none of them; and which body is nearest a point
// given in any other frame. The node resolves message frames with these before asking tf.
#pragma once

#include <Eigen/Geometry>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "deformable_sim/core/bodies/body_list.h"
#include "deformable_sim/core/session/commands.h"
#include "deformable_sim/core/session/simulation.h"

namespace deformable_sim::core {

/// A frame of the simulation's bodies, posed in the world.
struct BodyFrame {
  int body = -1;      ///< index into the bodies; -1: the name is not a frame of theirs
  std::string group;  ///< the node group, empty for the body's own frame
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< best-fit frame, world
};

/// The body or group frame called `frame`. Throws CommandError naming the groups the body has
/// when `frame` is <prefix><body>/<group> with a group the body lacks.
BodyFrame findBodyFrame(const BodyList& bodies, const std::string& prefix,
                        const std::string& frame);

/// Every frame findBodyFrame knows, by name, posed in the world: each body's, then its groups'.
/// What the node broadcasts on tf.
std::vector<std::pair<std::string, Eigen::Isometry3d>> allBodyFrames(const BodyList& bodies,
                                                                     const std::string& prefix);

/// "<prefix>a, <prefix>b": the bodies' frame names, for messages.
std::string bodyFrameNames(const BodyList& bodies, const std::string& prefix);

/// The node of any body closest to a point.
struct NearestNode {
  int body = -1;
  int node = -1;
  double distance = std::numeric_limits<double>::infinity();  ///< m
};
NearestNode nearestNode(const BodyList& bodies, const Eigen::Vector3d& point);

/// A wrench acting at `point` (world) on the nodes of the nearest body within that body's
/// wrench_radius of the point. Throws CommandError naming `frame`, the nearest body, its distance
/// and its wrench_radius when no body has a node that close.
WrenchCommand wrenchNearPoint(const Simulation& simulation, const std::string& frame,
                              const Eigen::Vector3d& point, const Eigen::Vector3d& force,
                              const Eigen::Vector3d& torque);

/// A wrench given in `frame` (posed by `target`): on the frame's body or group, acting at the
/// frame's origin; for any other frame, wrenchNearPoint at its origin. The source is `frame`.
WrenchCommand wrenchInFrame(const Simulation& simulation, const std::string& frame,
                            const BodyFrame& target, const Eigen::Vector3d& force,
                            const Eigen::Vector3d& torque);

}  // namespace deformable_sim::core
