#include "deformable_sim/ros/frame_resolver.h"

#include "deformable_sim/ros/conversions.h"

namespace deformable_sim::ros_layer {

std::string withoutLeadingSlash(const std::string& frame) {
  return !frame.empty() && frame[0] == '/' ? frame.substr(1) : frame;
}

core::BodyFrame FrameResolver::resolve(const core::Simulation& simulation,
                                       const std::string& frame_id) const {
  const std::string frame = withoutLeadingSlash(frame_id);
  if (frame.empty() || frame == world_frame_) return {};
  core::BodyFrame found = core::findBodyFrame(simulation.bodies(), prefix_, frame);
  if (found.body >= 0) return found;
  std::string error;
  const std::optional<Eigen::Isometry3d> pose = lookup(frame, &error);
  if (!pose) {
    throw core::CommandError("unknown frame '" + frame + "': not a body or group frame of this " +
                             "node (" + core::bodyFrameNames(simulation.bodies(), prefix_) +
                             ", and their groups) and not in tf (" + error + ")");
  }
  found.pose = *pose;
  return found;
}

std::optional<Eigen::Isometry3d> FrameResolver::lookupAt(const std::string& frame,
                                                         const ros::Time& time,
                                                         std::string* error) const {
  if (tf_.canTransform(world_frame_, frame, time)) {
    try {
      const Eigen::Isometry3d pose =
          toEigen(tf_.lookupTransform(world_frame_, frame, time).transform);
      if (pose.matrix().allFinite()) return pose;
    } catch (const tf2::TransformException&) {
    }
  }
  return lookup(frame, error);
}

std::optional<Eigen::Isometry3d> FrameResolver::lookup(const std::string& frame,
                                                       std::string* error) const {
  try {
    const Eigen::Isometry3d pose =
        toEigen(tf_.lookupTransform(world_frame_, frame, ros::Time(0)).transform);
    if (pose.matrix().allFinite()) return pose;
    if (error) *error = "frame '" + frame + "' has a non-finite pose in tf";
  } catch (const tf2::TransformException& e) {
    if (error) *error = e.what();
  }
  return std::nullopt;
}

}  // namespace deformable_sim::ros_layer
