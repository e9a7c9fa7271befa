// A session recorded as a lab would: a scene with a material the test keeps secret is driven by
// commands, the node's ~applied log is written to a bag, and what the lab measures goes beside
// it — tracked frames on /tf (120 Hz, with noise) and a force/torque sensor on a WrenchStamped
// topic (1 kHz, with noise). No ~state, and ~scene only when asked for (the node's nominal
// scene): the fit starts from a scene file or from that.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "deformable_sim/core/session/session.h"

namespace deformable_sim::test {

struct TrackedNode {
  std::string frame;
  Eigen::Vector3d at;  ///< rest position of a mesh node, m
};

struct LabRecording {
  std::string scene_yaml;     ///< with the secret values
  std::string body = "beam";  ///< the markers' and the sensor's
  /// The scene the lab's node ran with, recorded on ~scene (its nominal material, not the
  /// object's); empty: no ~scene in the bag.
  std::string node_scene_yaml;
  double duration = 2.0;  ///< s
  /// Commands by the step they are applied after.
  std::multimap<long, core::SessionCommand> commands;
  std::vector<TrackedNode> markers;
  double marker_rate = 120.0, marker_noise = 0.001;  ///< Hz, m (1 sigma)
  /// Every (1 / marker_outliers)-th marker sample a reading 5 cm off in z (a tracker's glitch).
  double marker_outliers = 0.0;
  /// The body's fixed nodes' reaction (or `sensor_grasp`'s wrench, or the contact wrench on the
  /// obstacle `sensor_link`), in the world frame, torque about its origin, on this topic; empty:
  /// no sensor.
  std::string sensor_topic = "/ft_sensor/wrench";
  std::string sensor_grasp, sensor_link;
  /// The frame the sensor reads in (its pose in the world, on /tf_static when it is not the
  /// world frame).
  std::string sensor_frame = "world";
  Eigen::Isometry3d sensor_pose = Eigen::Isometry3d::Identity();
  double sensor_rate = 1000.0, force_noise = 0.02, torque_noise = 0.002;  ///< Hz, N, N m
  double sensor_clock_offset = 0.0;  ///< s: the sensor's stamps run this far ahead
  /// rad/s: the sensor's frame turns about the world's z at its origin (a sensor on a moving
  /// link), on /tf at every sample; 0: still, on /tf_static.
  double sensor_turn_rate = 0.0;
  unsigned seed = 7;
};

/// Runs the scene and writes the bag at `path` (stamps from 1000 s).
void recordLab(const LabRecording& lab, const std::string& path);

}  // namespace deformable_sim::test
