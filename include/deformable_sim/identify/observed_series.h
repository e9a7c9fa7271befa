// Observations over time, and the simulated trajectory they are matched to by stamp: a 120 Hz
// tracker or a 1 kHz sensor is compared with the simulation interpolated at each sample's time,
// never assumed to come once per step.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace deformable_sim::identify {

/// What was measured of one observation: sample times (s after the session's step 0) and values.
struct MeasuredSeries {
  std::vector<double> times;
  std::vector<Eigen::VectorXd> values;
  /// A wrench's: per sample, its frame's pose in the world then (a sensor that moves); empty:
  /// the observation's one frame.
  std::vector<Eigen::Isometry3d> frames;
};

/// The simulated values at every step k, at time k dt.
struct SimulatedSeries {
  double dt = 0.01;  ///< s
  std::vector<Eigen::VectorXd> steps;

  /// Linear interpolation between the steps around `time` (clamped to the simulated span).
  Eigen::VectorXd at(double time) const;
};

}  // namespace deformable_sim::identify
