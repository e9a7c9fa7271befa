// The ROS face of a simulation: a scene stepped on a timer, driven by topics and services,
// published as state, tf, markers, stats and diagnostics. Everything physical happens in the core;
// this class turns messages into core commands and results into messages.
#pragma once

#include <diagnostic_updater/diagnostic_updater.h>
#include <dynamic_reconfigure/server.h>
#include <geometry_msgs/WrenchStamped.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/Marker.h>

#include <Eigen/Geometry>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "deformable_sim/Applied.h"
#include "deformable_sim/BodyState.h"
#include "deformable_sim/FixedNodes.h"
#include "deformable_sim/Grasp.h"
#include "deformable_sim/NodeWrench.h"
#include "deformable_sim/SetGrasp.h"
#include "deformable_sim/SimConfig.h"
#include "deformable_sim/Stats.h"
#include "deformable_sim/Step.h"
#include "deformable_sim/core/commands.h"
#include "deformable_sim/core/scene.h"
#include "deformable_sim/core/session.h"
#include "deformable_sim/core/simulation.h"
#include "deformable_sim/ros/refusal_log.h"

namespace deformable_sim::ros_layer {

class SimNode {
 public:
  /// Reads the parameters and the scene (~scene, or the built-in default scene) and starts the
  /// timer. Throws std::runtime_error naming the parameter or scene key when it cannot start.
  SimNode(ros::NodeHandle& node, ros::NodeHandle& private_node);

 private:
  /// Where a frame named in a message is, and what of the simulation it names.
  struct FrameTarget {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< in world_frame
    int body = -1;      ///< a body's frame or one of its groups' frames; -1 for other frames
    std::string group;  ///< the group, when the frame is a group's
  };

  void readParameters(ros::NodeHandle& private_node);
  /// Reads the meshes and starts the session (throws std::runtime_error naming the scene key).
  void buildSimulation();
  /// Forgets what belongs to the running episode: wrench times, grasp frames, reports.
  void clearTickState();
  /// Applies a command as ~applied records it; throws core::CommandError when refused.
  int apply(const core::SessionCommand& command);
  void publishApplied(const core::AppliedCommand& applied);
  void publishScene();
  core::Simulation& sim() { return session_->simulation(); }
  const core::Simulation& sim() const { return session_->simulation(); }
  void onTimer(const ros::TimerEvent& event);
  void advance(int steps);
  void publishState();
  void publishFrames();
  void publishMarkers();
  void publishStats();

  void onWrench(const geometry_msgs::WrenchStamped::ConstPtr& message);
  void onNodeWrench(const NodeWrench::ConstPtr& message);
  void onFixedNodes(const FixedNodes::ConstPtr& message);
  void onGrasp(const Grasp::ConstPtr& message);
  bool onSetGrasp(SetGrasp::Request& request, SetGrasp::Response& response);
  /// Attaches or releases; returns "" on success, else why it was refused.
  std::string applyGrasp(const Grasp& message, uint32_t& nodes);
  /// The pose of a grasp's frame now (the last known one if tf has none).
  Eigen::Isometry3d graspFramePose(const std::string& name);
  void publishGrasps();
  /// Reads the robot description once (scene key urdf.file, else the robot_description
  /// parameter); false with `error` set when there is none or it is not valid.
  bool loadUrdf(std::string& error);
  /// Poses the URDF links' obstacles from tf and hands every obstacle to the simulation; false
  /// while tf has not yet placed them all.
  bool updateObstacles();
  bool onReset(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  bool onPause(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  bool onResume(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  bool onStep(Step::Request& request, Step::Response& response);
  void onReconfigure(SimConfig& config);
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);

  /// Resolves a frame id ("" means world_frame); false with `error` set if it is unknown.
  bool resolveFrame(const std::string& frame_id, FrameTarget& target, std::string& error) const;
  std::string bodyFrame(int body) const;
  void refuse(const std::string& topic, const std::string& reason);

  // Parameters.
  std::string scene_path_;
  std::string world_frame_;
  std::string frame_prefix_;
  double rate_hz_ = 100.0;
  int substeps_ = 1;
  double wrench_timeout_s_ = 0.0;  ///< 0: wrenches stay until replaced
  double stats_rate_hz_ = 10.0;
  double marker_rate_hz_ = 30.0;
  double strain_colour_scale_ = 0.1;
  core::CommandLimits limits_;

  // Simulation.
  core::SceneSpec scene_;
  std::string scene_text_;  ///< the scene file's text, for ~scene
  std::unique_ptr<core::Session> session_;
  std::vector<core::PlacedShape> requested_obstacles_;  ///< as last applied, before recording
  Applied recording_;  ///< the message of the command being applied, published once it took effect
  std::vector<std::vector<core::Triangle>> surfaces_;
  std::vector<core::StepReport> reports_;
  std::map<std::string, ros::Time> wrench_times_;  ///< for ~wrench_timeout
  bool paused_ = false;
  double step_time_s_ = 0.0;
  long recoveries_seen_ = 0;     ///< the watchdog's recoveries, all bodies, this episode
  ros::WallTime last_recovery_;  ///< when the last one happened (zero: never)
  std::deque<std::pair<ros::Time, double>> sim_time_samples_;  ///< (ROS time, sim time)
  double real_time_factor_ = 0.0;
  RefusalLog refusals_;

  // ROS plumbing.
  ros::Timer timer_;
  ros::Publisher state_pub_, stats_pub_, mesh_pub_, markers_pub_, applied_pub_, scene_pub_;
  ros::Subscriber wrench_sub_, node_wrench_sub_, fixed_nodes_sub_, grasp_sub_;
  ros::ServiceServer reset_srv_, pause_srv_, resume_srv_, step_srv_, grasp_srv_;
  ros::NodeHandle private_node_;
  std::map<std::string, std::string> grasp_frames_;  ///< grasp name -> tf frame it follows
  std::map<std::string, ros::Publisher> grasp_wrench_pubs_;
  std::vector<ros::Publisher> reaction_pubs_;  ///< per body: what its fixed nodes exert
  bool urdf_loaded_ = false;
  std::map<std::string, std::vector<core::PlacedShape>> urdf_shapes_;  ///< link -> shapes
  struct LinkObstacle {
    std::string link;
    core::PlacedShape local;                  ///< pose in the link's frame
    std::optional<core::PlacedShape> placed;  ///< in the world, once tf had the link
  };
  std::vector<LinkObstacle> link_obstacles_;
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  diagnostic_updater::Updater diagnostics_;
  boost::recursive_mutex reconfigure_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<SimConfig>> reconfigure_;
  SimConfig applied_config_;  ///< what is in effect
  SimConfig scene_config_;    ///< the scene's own values
  ros::Time last_stats_, last_markers_;
  BodyState state_message_;
  visualization_msgs::Marker mesh_message_;
  std::vector<double> strain_;
};

}  // namespace deformable_sim::ros_layer
