// What the node publishes of contact, every tick while the contact effect is on: ~contacts,
// every pair that touched in the last step; and for each robot link the scene makes an obstacle,
// ~contacts/<link>/wrench: what the bodies exert on the link, in its frame about its origin (a
// finger's force sensor; zero while nothing touches it).
#pragma once

#include <ros/ros.h>

#include <string>
#include <utility>
#include <vector>

#include "deformable_sim/core/driver/linked_obstacles.h"
#include "deformable_sim/core/outputs/contact_pairs.h"
#include "deformable_sim/core/session/session.h"

namespace deformable_sim::ros_layer {

class ContactOutputs {
 public:
  ContactOutputs(ros::NodeHandle& private_node, const std::vector<std::string>& links,
                 std::string world_frame);

  /// For the last step, stamped `stamp` (the instant it shows); `link_pose` places the links
  /// (one not in tf now gets no wrench).
  void publish(const core::Session& session, const core::LinkedObstacles::FramePose& link_pose,
               const ros::Time& stamp);

 private:
  std::string world_frame_;
  ros::Publisher contacts_pub_;
  std::vector<std::pair<std::string, ros::Publisher>> link_pubs_;
  std::vector<core::ContactPair> pairs_;
};

}  // namespace deformable_sim::ros_layer
