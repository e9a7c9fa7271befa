#include "deformable_sim/ros/body_frames.h"

#include "deformable_sim/core/rigid_frame.h"
#include "deformable_sim/ros/conversions.h"

namespace deformable_sim::ros_layer {

std::vector<geometry_msgs::TransformStamped> bodyFrames(const std::vector<core::Body>& bodies,
                                                        const std::string& world_frame,
                                                        const std::string& prefix,
                                                        const ros::Time& stamp) {
  std::vector<geometry_msgs::TransformStamped> frames;
  auto add = [&](const std::string& child, const core::RigidFrame& frame) {
    geometry_msgs::TransformStamped t;
    t.header.stamp = stamp;
    t.header.frame_id = world_frame;
    t.child_frame_id = child;
    t.transform = toTransform(core::toIsometry(frame));
    frames.push_back(t);
  };
  for (const core::Body& body : bodies) {
    add(prefix + body.name(),
        core::bestFitFrame(body.positions(), body.restPositions(), body.nodalMasses()));
    for (const auto& [name, nodes] : body.groups()) {
      add(prefix + body.name() + "/" + name,
          core::bestFitFrame(body.positions(), body.restPositions(), body.nodalMasses(), nodes));
    }
  }
  return frames;
}

}  // namespace deformable_sim::ros_layer
