// What a lab measured during a recorded session, read from the same bag: tracked frames from /tf
// (children of the world frame) and force/torque sensors (WrenchStamped topics), for a fit.
#pragma once

#include <ros/time.h>

#include <string>
#include <vector>

#include "deformable_sim/identify/experiment.h"
#include "deformable_sim/identify/session_clock.h"

namespace deformable_sim::ros_layer {

struct Measurements {
  std::vector<identify::MeasuredSeries> series;  ///< per observation, in simulated time
  std::vector<Eigen::Isometry3d> sensor_frames;  ///< per observation: a wrench's frame, world
  std::vector<long> outside;  ///< per observation: samples outside the session, left out
};

/// Reads every observation's samples from the bag at `path`, each at the simulated time `clock`
/// gives its stamp (samples before the episode are left out). A wrench's frame is the world frame
/// or a frame in the bag's /tf or /tf_static (its pose at the first sample). Throws
/// identify::FitSpecError naming the key: a topic or a frame the bag does not hold, a tracked frame
/// whose parent is not the world frame.
Measurements readMeasurements(const std::string& path,
                              const std::vector<identify::ObservationSpec>& observations,
                              const std::string& world_frame, const identify::SessionClock& clock);

}  // namespace deformable_sim::ros_layer
