#include "deformable_sim/ros/body_frames.h"

#include "deformable_sim/core/driver/body_frame_lookup.h"
#include "deformable_sim/ros/conversions.h"

namespace deformable_sim::ros_layer {

std::vector<geometry_msgs::TransformStamped> bodyFrames(const core::BodyList& bodies,
                                                        const std::string& world_frame,
                                                        const std::string& prefix,
                                                        const ros::Time& stamp) {
  std::vector<geometry_msgs::TransformStamped> frames;
  for (const auto& [name, pose] : core::allBodyFrames(bodies, prefix)) {
    geometry_msgs::TransformStamped t;
    t.header.stamp = stamp;
    t.header.frame_id = world_frame;
    t.child_frame_id = name;
    t.transform = toTransform(pose);
    frames.push_back(t);
  }
  return frames;
}

}  // namespace deformable_sim::ros_layer
