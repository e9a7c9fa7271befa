// Grasps as the node runs them: a Grasp message (topic or service) becomes a core command; each
// grasp follows its tf frame, moved evenly over a tick's substeps; what each grasp pushes with
// (~grasps/<name>/wrench) and where the object sits in the hand (tf <name>/object) go out.
#pragma once

#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>

#include <functional>
#include <map>
#include <string>

#include "deformable_sim/Grasp.h"
#include "deformable_sim/core/driver/grasp_follower.h"
#include "deformable_sim/core/session/session.h"
#include "deformable_sim/ros/frame_resolver.h"
#include "deformable_sim/ros/robot_links.h"

namespace deformable_sim::ros_layer {

class NodeGrasps {
 public:
  /// Applies a command as the node records it; throws core::CommandError when refused.
  using Apply = std::function<int(const core::SessionCommand&)>;

  NodeGrasps(const ros::NodeHandle& private_node, const FrameResolver& frames, RobotLinks& links,
             Apply apply)
      : node_(private_node), frames_(frames), links_(links), apply_(std::move(apply)) {}

  /// Attaches or releases; returns the number of nodes. Throws core::CommandError saying why not.
  uint32_t handle(const core::Session& session, const Grasp& message);
  /// Where each grasp's frame goes over the next substeps: from its pose now to tf's.
  void planMoves(const core::CommandProcessor& commands);
  /// Moves every grasp to its pose after substep `s` of `steps` (1 <= s <= steps).
  void move(int s, int steps);
  /// The grasps' wrenches, and their objects' tf frames through `broadcaster` unless it is null.
  void publish(const core::Session& session, const ros::Time& stamp,
               tf2_ros::TransformBroadcaster* broadcaster);
  /// Forgets every grasp (after a reset).
  void clear();

 private:
  core::GraspCommand attachCommand(const core::Simulation& simulation, const Grasp& message);
  core::NodeTarget linkRegion(const Grasp& message, const std::string& frame);

  ros::NodeHandle node_;
  const FrameResolver& frames_;
  RobotLinks& links_;
  Apply apply_;
  core::GraspFollower follower_;
  std::map<std::string, ros::Publisher> wrench_pubs_;
};

}  // namespace deformable_sim::ros_layer
