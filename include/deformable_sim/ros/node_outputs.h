// What the node publishes of a running session: ~state and tf every tick, ~mesh and ~markers at
// ~marker_rate (with contact forces), ~stats at ~stats_rate, ~reactions/<body>, and /diagnostics.
// rviz is told to forget the node's markers when it stops (DELETEALL); ~markers start with one
// each time, and the meshes on ~mesh have a lifetime, so that those of a run that died go too.
#pragma once

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>
#include <visualization_msgs/Marker.h>

#include <vector>

#include "deformable_sim/BodyState.h"
#include "deformable_sim/core/driver/once_per_stamp.h"
#include "deformable_sim/core/driver/periodic_schedule.h"
#include "deformable_sim/core/driver/refusal_log.h"
#include "deformable_sim/core/driver/tick_status.h"
#include "deformable_sim/core/outputs/contact_pairs.h"
#include "deformable_sim/core/session/session.h"
#include "deformable_sim/ros/markers.h"
#include "deformable_sim/ros/node_parameters.h"

namespace deformable_sim::ros_layer {

using core::TickStatus;

class NodeOutputs {
 public:
  NodeOutputs(ros::NodeHandle& node, ros::NodeHandle& private_node, const NodeParameters& params,
              const core::Session& session);

  /// ~state, the bodies' tf frames and ~reactions, stamped `stamp`: the clock time of the
  /// simulated instant they show (core/driver/simulated_instants.h). tf is sent once a stamp: a
  /// state that has not moved on since the last tick repeats no transform. True if tf was sent.
  bool publishState(const core::Session& session, const ros::Time& stamp);
  /// ~mesh, ~markers and ~stats when each is due at clock time `now`, stamped `stamp`; and
  /// /diagnostics.
  void publishPeriodic(const core::Session& session, const TickStatus& status,
                       const core::RefusalLog& refusals, const ros::Time& now,
                       const ros::Time& stamp);
  /// DELETEALL on ~mesh and ~markers.
  void clearMarkers();

  tf2_ros::TransformBroadcaster& broadcaster() { return broadcaster_; }

 private:
  void publishMarkers(const core::Session& session, const std_msgs::Header& header);
  void publishStats(const core::Session& session, const TickStatus& status,
                    const core::RefusalLog& refusals, const ros::Time& stamp);
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& out);

  const NodeParameters& params_;
  ros::Publisher state_pub_, stats_pub_, mesh_pub_, markers_pub_;
  std::vector<ros::Publisher> reaction_pubs_;  ///< per body: what its fixed nodes exert
  tf2_ros::TransformBroadcaster broadcaster_;
  diagnostic_updater::Updater diagnostics_;
  core::PeriodicSchedule marker_schedule_, stats_schedule_;
  core::OncePerStamp tf_stamps_;
  SurfaceMarkers surfaces_;
  std::vector<core::ContactPair> contact_pairs_;
  BodyState state_message_;
  const core::Session* session_ = nullptr;  ///< for the diagnostics callback
  const TickStatus* status_ = nullptr;
  const core::RefusalLog* refusals_ = nullptr;
};

}  // namespace deformable_sim::ros_layer
