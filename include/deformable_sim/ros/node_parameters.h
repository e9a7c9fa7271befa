// The node's private parameters, read and checked once at start.
#pragma once

#include <ros/node_handle.h>

#include <string>

#include "deformable_sim/core/session/commands.h"
#include "deformable_sim/core/session/scene.h"
#include "deformable_sim/ros/markers.h"

namespace deformable_sim::ros_layer {

struct NodeParameters {
  std::string scene_path;  ///< ~scene; empty: the built-in default scene
  std::string scene_text;  ///< the scene file's text, for ~scene
  core::SceneSpec scene;   ///< dt set from ~rate and ~substeps
  std::string world_frame = "world";
  std::string frame_prefix;  ///< default: the node's namespace
  double rate_hz = 100.0;
  /// Why dt is not the scene's (a ~rate that sets another), for a warning; empty when it is.
  std::string rate_note;
  int substeps = 1;
  bool start_paused = false;
  double wrench_timeout_s = 0.0;  ///< 0: wrenches stay until replaced
  double stats_rate_hz = 10.0;
  double marker_rate_hz = 30.0;
  /// Robot links are placed where tf had them this long ago, interpolated between its samples:
  /// they move smoothly however their joint states arrive (a finger that jumps every other tick
  /// would shake what it holds by friction).
  double link_delay_s = 0.05;
  double strain_colour_scale = kDefaultStrainScale;
  int max_steps_per_call = 1000;  ///< the most ~step takes in one call
  core::CommandLimits limits;
};

/// Throws std::runtime_error naming the parameter (or the scene file's key) that is wrong.
NodeParameters readNodeParameters(const ros::NodeHandle& private_node);

}  // namespace deformable_sim::ros_layer
