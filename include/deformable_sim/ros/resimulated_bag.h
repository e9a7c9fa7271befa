// The bag a re-simulation writes, so that it plays back like the recording: the re-simulated
// ~state, /tf and ~mesh at the times of the recorded states, and the ~scene they belong to.
#pragma once

#include <ros/time.h>
#include <rosbag/bag.h>
#include <std_msgs/Header.h>
#include <visualization_msgs/Marker.h>

#include <string>
#include <vector>

#include "deformable_sim/BodyState.h"
#include "deformable_sim/Scene.h"
#include "deformable_sim/core/driver/once_per_stamp.h"
#include "deformable_sim/core/driver/periodic_schedule.h"
#include "deformable_sim/core/session/resimulation.h"
#include "deformable_sim/ros/markers.h"

namespace deformable_sim::ros_layer {

class ResimulatedBag {
 public:
  /// `simulation` gives the bodies' surfaces; `state_headers` are the recorded states' headers
  /// (a compared state's `source` indexes them); both are read, not kept. `marker_rate` is in Hz
  /// of simulated time; `colours` are the bodies' (core::bodyColours). Throws ReplayError when the
  /// file cannot be written.
  ResimulatedBag(const std::string& path, const std::string& node, const Scene& scene,
                 const core::Simulation& simulation,
                 const std::vector<std_msgs::Header>& state_headers, double marker_rate,
                 std::vector<Eigen::Vector3d> colours);

  /// The re-simulated state (with the recorded one's header), the bodies' frames with the first
  /// body, and its surface at the marker rate.
  void write(const core::ComparedState& state);
  /// Closes the bag (with the scene at its own stamp if no state came).
  void close();

 private:
  void writeScene(const ros::Time& stamp);
  void writeFrames(const core::ComparedState& state, const ros::Time& stamp);
  void writeSurface(const core::ComparedState& state, const std_msgs::Header& header);
  bool markerDue(const core::ComparedState& state);

  rosbag::Bag bag_;
  std::string node_;
  const Scene& scene_;
  const std::vector<std_msgs::Header>& state_headers_;
  double marker_period_;  ///< s of simulated time
  core::PeriodicSchedule marker_schedule_;
  core::OncePerStamp tf_stamps_;
  SurfaceMarkers surfaces_;
  bool scene_written_ = false;
  // Which step the last state belonged to, and whether that step gets markers.
  long last_episode_ = -1, last_step_ = -1;
  bool marker_due_ = false;
  BodyState state_message_;  ///< kept between states so that its arrays are reused
};

}  // namespace deformable_sim::ros_layer
