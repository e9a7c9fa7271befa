// The ROS face of a simulation: a scene stepped on a timer, driven by topics and services. This
// class wires them; parameters, frames, grasps, robot links, live tuning and outputs each have
// their own file, and everything physical or geometric happens in the core.
#pragma once

#include <geometry_msgs/WrenchStamped.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "deformable_sim/Applied.h"
#include "deformable_sim/FixedNodes.h"
#include "deformable_sim/Grasp.h"
#include "deformable_sim/NodeWrench.h"
#include "deformable_sim/SetGrasp.h"
#include "deformable_sim/Step.h"
#include "deformable_sim/core/driver/real_time_factor.h"
#include "deformable_sim/core/driver/refusal_log.h"
#include "deformable_sim/core/driver/simulated_instants.h"
#include "deformable_sim/core/driver/slow_tick_watch.h"
#include "deformable_sim/core/driver/tick_pacer.h"
#include "deformable_sim/core/driver/wrench_timeouts.h"
#include "deformable_sim/core/session/session.h"
#include "deformable_sim/ros/contact_outputs.h"
#include "deformable_sim/ros/frame_resolver.h"
#include "deformable_sim/ros/live_tuning.h"
#include "deformable_sim/ros/node_grasps.h"
#include "deformable_sim/ros/node_obstacles.h"
#include "deformable_sim/ros/node_outputs.h"
#include "deformable_sim/ros/node_parameters.h"
#include "deformable_sim/ros/obstacle_mesh_messages.h"
#include "deformable_sim/ros/robot_links.h"

namespace deformable_sim::ros_layer {

class SimNode {
 public:
  /// Reads the parameters and the scene (~scene, or the built-in default scene) and starts the
  /// timer. Throws std::runtime_error naming the parameter or scene key when it cannot start.
  SimNode(ros::NodeHandle& node, ros::NodeHandle& private_node);
  /// Tells rviz to forget this node's markers (before it leaves).
  void clearMarkers() { outputs_->clearMarkers(); }

 private:
  void startSession();
  void logStart() const;
  /// Applies a command as ~applied records it; throws core::CommandError when refused.
  int apply(const core::SessionCommand& command);
  void publishScene();
  core::Simulation& sim() { return session_->simulation(); }
  void onTimer(const ros::TimerEvent& event);
  void advance(int steps);
  /// Warns (throttled) while the node has been slower than real time for a while.
  void watchRealTime(bool stepped);
  /// The clock time of the instant the bodies are at: what every output is stamped with.
  ros::Time shownInstant() const;
  /// ~state, tf, reactions, contacts and grasps; link poses for the contact wrenches at `now`.
  void publishState(const ros::Time& now);
  void refuse(const std::string& topic, const std::string& reason);

  void onWrench(const geometry_msgs::WrenchStamped::ConstPtr& message);
  void onNodeWrench(const NodeWrench::ConstPtr& message);
  void onFixedNodes(const FixedNodes::ConstPtr& message);
  void onGrasp(const Grasp::ConstPtr& message);
  bool onSetGrasp(SetGrasp::Request& request, SetGrasp::Response& response);
  bool onReset(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  bool onPause(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  bool onResume(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  bool onStep(Step::Request& request, Step::Response& response);

  NodeParameters params_;
  std::unique_ptr<core::Session> session_;
  Applied recording_;  ///< the message of the command being applied, published once it took effect
  core::MeshCatalogue obstacle_meshes_;  ///< meshes recorded in ~scene and ~applied, by id
  TickStatus status_;
  core::RealTimeFactor real_time_factor_;
  core::TickPacer pacer_{1.0};  ///< restarted with the node's period before the first tick
  core::SimulatedInstants instants_;
  core::SlowTickWatch slow_ticks_;
  core::WrenchTimeouts wrench_timeouts_;
  core::RefusalLog refusals_;
  ros::WallTime last_recovery_;  ///< zero: never

  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  FrameResolver frames_;
  RobotLinks robot_links_;
  std::optional<NodeObstacles> obstacles_;  ///< once the session is up
  std::unique_ptr<NodeOutputs> outputs_;
  std::optional<ContactOutputs> contact_outputs_;  ///< with the contact effect
  std::unique_ptr<NodeGrasps> grasps_;
  std::unique_ptr<LiveTuning> tuning_;
  ros::Timer timer_;
  ros::Publisher applied_pub_, scene_pub_;
  std::vector<ros::Subscriber> subscribers_;
  std::vector<ros::ServiceServer> services_;
};

}  // namespace deformable_sim::ros_layer
