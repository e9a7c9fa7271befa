#include "deformable_sim/ros/node_parameters.h"

#include <ros/this_node.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "deformable_sim/core/session/live_settings.h"
#include "deformable_sim/io/scene_file.h"
#include "deformable_sim/ros/frame_resolver.h"

namespace deformable_sim::ros_layer {

namespace {

// Reads a private parameter, keeping `value` (the default) when it is not set.
template <typename T>
void param(const ros::NodeHandle& node, const std::string& name, T& value) {
  node.param(name, value, value);
}

void require(bool ok, const std::string& message) {
  if (!ok) throw std::runtime_error(message);
}

void readScene(const ros::NodeHandle& node, NodeParameters& p) {
  param(node, "scene", p.scene_path);
  try {
    if (!p.scene_path.empty()) p.scene_text = io::readSceneText(p.scene_path);
    p.scene = io::sceneFromFileText(p.scene_text, p.scene_path);
  } catch (const io::SceneError& e) {
    throw std::runtime_error(std::string("~scene: ") + e.what());
  }
}

void readFrames(const ros::NodeHandle& node, NodeParameters& p) {
  param(node, "world_frame", p.world_frame);
  p.world_frame = withoutLeadingSlash(p.world_frame);
  // Several instances side by side: frames are prefixed by the node's namespace by default.
  const std::string ns = withoutLeadingSlash(ros::this_node::getNamespace());
  p.frame_prefix = ns.empty() ? "" : ns + "/";
  param(node, "frame_prefix", p.frame_prefix);
  p.frame_prefix = withoutLeadingSlash(p.frame_prefix);
}

void readTiming(const ros::NodeHandle& node, NodeParameters& p) {
  param(node, "substeps", p.substeps);
  require(p.substeps >= 1, "~substeps: must be >= 1");
  p.rate_hz = 1.0 / (p.scene.dt * p.substeps);
  param(node, "rate", p.rate_hz);
  require(p.rate_hz >= core::kMinRate && p.rate_hz <= core::kMaxRate,
          "~rate: must be finite and > 0 Hz, at most 1e5 (at least 1e-3)");
  const double scene_dt = p.scene.dt;
  p.scene.dt = 1.0 / (p.rate_hz * p.substeps);
  if (std::abs(p.scene.dt - scene_dt) > 1e-9 * scene_dt) {
    // A ~rate is also what live tuning leaves on the parameter server: say which dt is used.
    char why[400];
    std::snprintf(why, sizeof why,
                  "~rate %g Hz on the parameter server (%s) sets dt %g s, not the scene's %g s; "
                  "a rate set by an earlier node or its live tuning stays there until "
                  "`rosparam delete %s`",
                  p.rate_hz, node.resolveName("rate").c_str(), p.scene.dt, scene_dt,
                  node.resolveName("rate").c_str());
    p.rate_note = why;
  }
  param(node, "start_paused", p.start_paused);
  param(node, "wrench_timeout", p.wrench_timeout_s);
  param(node, "stats_rate", p.stats_rate_hz);
  param(node, "marker_rate", p.marker_rate_hz);
  param(node, "link_delay", p.link_delay_s);
  param(node, "max_steps_per_call", p.max_steps_per_call);
  require(p.wrench_timeout_s >= 0.0, "~wrench_timeout: must be >= 0 s");
  require(p.stats_rate_hz > 0.0, "~stats_rate: must be > 0 Hz");
  require(p.marker_rate_hz > 0.0, "~marker_rate: must be > 0 Hz");
  require(p.link_delay_s >= 0.0 && p.link_delay_s <= 10.0, "~link_delay: must be in [0, 10] s");
  require(p.max_steps_per_call >= 1, "~max_steps_per_call: must be >= 1");
}

void readLimits(const ros::NodeHandle& node, NodeParameters& p) {
  param(node, "strain_colour_scale", p.strain_colour_scale);
  require(p.strain_colour_scale > 0.0, "~strain_colour_scale: must be > 0");
  // Unset bounds stay 0: each body's own (core::wrenchBounds).
  param(node, "max_force", p.limits.max_force);
  param(node, "max_torque", p.limits.max_torque);
  param(node, "max_target_distance", p.limits.max_target_distance);
  require(p.limits.max_force >= 0.0 && p.limits.max_torque >= 0.0,
          "~max_force, ~max_torque: must be >= 0 (0 or unset: the body's own bound)");
  require(p.limits.max_target_distance > 0.0, "~max_target_distance: must be > 0 m");
}

}  // namespace

NodeParameters readNodeParameters(const ros::NodeHandle& private_node) {
  NodeParameters p;
  readScene(private_node, p);
  readFrames(private_node, p);
  readTiming(private_node, p);
  readLimits(private_node, p);
  return p;
}

}  // namespace deformable_sim::ros_layer
