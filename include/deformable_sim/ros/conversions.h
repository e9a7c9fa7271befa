// Between ROS messages and the core's Eigen types and commands. No logging, no node handles.
#pragma once

#include <geometry_msgs/Point.h>
#include <geometry_msgs/Transform.h>
#include <geometry_msgs/Vector3.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "deformable_sim/BodyState.h"
#include "deformable_sim/FixedNodes.h"
#include "deformable_sim/NodeWrench.h"
#include "deformable_sim/core/body.h"
#include "deformable_sim/core/commands.h"
#include "deformable_sim/core/rigid_frame.h"

namespace deformable_sim::ros_layer {

inline Eigen::Vector3d toEigen(const geometry_msgs::Point& p) { return {p.x, p.y, p.z}; }
inline Eigen::Vector3d toEigen(const geometry_msgs::Vector3& v) { return {v.x, v.y, v.z}; }
geometry_msgs::Point toPoint(const Eigen::Vector3d& v);
geometry_msgs::Vector3 toVector3(const Eigen::Vector3d& v);
Eigen::Isometry3d toEigen(const geometry_msgs::Transform& t);
geometry_msgs::Transform toTransform(const Eigen::Isometry3d& pose);

/// A NodeWrench whose frame is `frame_in_world` (the pose of header.frame_id in the world frame).
core::WrenchCommand toCommand(const NodeWrench& message, const Eigen::Isometry3d& frame_in_world);

/// A FixedNodes message whose frame is `frame_in_world` (the region is tested in that frame).
/// Throws core::CommandError for an unknown action or region code.
core::FixCommand toCommand(const FixedNodes& message, const Eigen::Isometry3d& frame_in_world);

/// Fills `message` (kept between calls so its arrays are reused) with the body's state.
void fillState(const core::Body& body, BodyState& message);

}  // namespace deformable_sim::ros_layer
