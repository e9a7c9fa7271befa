// Between ROS messages and the core's Eigen types and commands. No logging, no node handles.
#pragma once

#include <geometry_msgs/Point.h>
#include <geometry_msgs/Transform.h>
#include <geometry_msgs/Vector3.h>
#include <geometry_msgs/WrenchStamped.h>
#include <tf2_eigen/tf2_eigen.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "deformable_sim/BodyState.h"
#include "deformable_sim/FixedNodes.h"
#include "deformable_sim/NodeWrench.h"
#include "deformable_sim/core/bodies/body.h"
#include "deformable_sim/core/bodies/rigid_frame.h"
#include "deformable_sim/core/session/commands.h"

namespace deformable_sim::ros_layer {

inline Eigen::Vector3d toEigen(const geometry_msgs::Point& p) { return {p.x, p.y, p.z}; }
inline Eigen::Vector3d toEigen(const geometry_msgs::Vector3& v) { return {v.x, v.y, v.z}; }
inline geometry_msgs::Point toPoint(const Eigen::Vector3d& v) { return tf2::toMsg(v); }
inline geometry_msgs::Vector3 toVector3(const Eigen::Vector3d& v) {
  geometry_msgs::Vector3 m;
  return tf2::toMsg(v, m);
}
/// The rotation is normalised: a message's quaternion need not be of unit length.
inline Eigen::Isometry3d toEigen(geometry_msgs::Transform t) {
  Eigen::Quaterniond q;
  tf2::fromMsg(t.rotation, q);
  t.rotation = tf2::toMsg(q.normalized());
  return tf2::transformToEigen(t);
}
inline geometry_msgs::Transform toTransform(const Eigen::Isometry3d& pose) {
  return tf2::eigenToTransform(pose).transform;
}

/// `wrench` as a sensor at `frame` (its pose in the world) reads it (core::seenFrom).
geometry_msgs::WrenchStamped toMessage(const core::Wrench& wrench, const std::string& frame_id,
                                       const Eigen::Isometry3d& frame, const ros::Time& stamp);

/// The box or sphere region of a message that has one (FixedNodes, Grasp), tested in `frame`;
/// false, and `nodes` as it was, for its other region codes.
template <typename Message>
bool setRegion(const Message& m, const Eigen::Isometry3d& frame, core::NodeTarget& nodes) {
  if (m.region == Message::REGION_BOX) {
    nodes.box = core::Box{toEigen(m.box_min), toEigen(m.box_max)};
  } else if (m.region == Message::REGION_SPHERE) {
    nodes.sphere = core::Sphere{toEigen(m.sphere_center), m.sphere_radius};
  } else {
    return false;
  }
  nodes.region_pose = frame;
  return true;
}

/// A NodeWrench whose frame is `frame_in_world` (the pose of header.frame_id in the world frame).
core::WrenchCommand toCommand(const NodeWrench& message, const Eigen::Isometry3d& frame_in_world);

/// A FixedNodes message whose frame is `frame_in_world` (the region is tested in that frame).
/// Throws core::CommandError for an unknown action or region code.
core::FixCommand toCommand(const FixedNodes& message, const Eigen::Isometry3d& frame_in_world);

/// Fills `message` (kept between calls so its arrays are reused) with the body's state.
void fillState(const core::Body& body, BodyState& message);

}  // namespace deformable_sim::ros_layer
