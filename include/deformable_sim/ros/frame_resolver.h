// Where a frame named in a message is: the world frame, a body's or node group's frame of this
// node (the core's best-fit frames), or any other frame tf knows.
#pragma once

#include <tf2_ros/buffer.h>

#include <Eigen/Geometry>
#include <optional>
#include <string>

#include "deformable_sim/core/driver/body_frame_lookup.h"
#include "deformable_sim/core/session/simulation.h"

namespace deformable_sim::ros_layer {

std::string withoutLeadingSlash(const std::string& frame);

class FrameResolver {
 public:
  FrameResolver(const tf2_ros::Buffer& tf, std::string world_frame, std::string prefix)
      : tf_(tf), world_frame_(std::move(world_frame)), prefix_(std::move(prefix)) {}

  /// The frame's pose in the world frame and what of the simulation it names ("" is the world
  /// frame). Throws core::CommandError naming the frame when it is neither the simulation's nor
  /// in tf, or its pose is not finite.
  core::BodyFrame resolve(const core::Simulation& simulation, const std::string& frame_id) const;
  /// The latest pose of a tf frame in the world frame; nullopt, with `error` set, if there is none.
  std::optional<Eigen::Isometry3d> lookup(const std::string& frame, std::string* error) const;
  /// Its pose at `time`, interpolated by tf; the latest while tf has nothing that recent or old.
  std::optional<Eigen::Isometry3d> lookupAt(const std::string& frame, const ros::Time& time,
                                            std::string* error) const;

  const std::string& worldFrame() const { return world_frame_; }
  const std::string& prefix() const { return prefix_; }

 private:
  const tf2_ros::Buffer& tf_;
  std::string world_frame_;
  std::string prefix_;
};

}  // namespace deformable_sim::ros_layer
