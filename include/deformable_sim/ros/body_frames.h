// The tf frames of a simulation's bodies and node groups: their best-fit rigid motions.
#pragma once

#include <geometry_msgs/TransformStamped.h>
#include <ros/time.h>

#include <string>
#include <vector>

#include "deformable_sim/core/bodies/body_list.h"

namespace deformable_sim::ros_layer {

/// world_frame -> <prefix><body> for every body and world_frame -> <prefix><body>/<group> for
/// every node group, stamped `stamp`.
std::vector<geometry_msgs::TransformStamped> bodyFrames(const core::BodyList& bodies,
                                                        const std::string& world_frame,
                                                        const std::string& prefix,
                                                        const ros::Time& stamp);

}  // namespace deformable_sim::ros_layer
