#include "deformable_sim/ros/node_obstacles.h"

#include <ros/console.h>

#include <utility>

namespace deformable_sim::ros_layer {

NodeObstacles::NodeObstacles(const core::SceneSpec& scene, RobotLinks& links,
                             const FrameResolver& frames, double link_delay_s, Apply apply)
    : frames_(frames),
      link_delay_s_(link_delay_s),
      apply_(std::move(apply)),
      obstacles_(sceneObstacles(scene, links)) {}

std::optional<Eigen::Isometry3d> NodeObstacles::linkPose(const std::string& link,
                                                         const ros::Time& now,
                                                         std::string* error) const {
  if (now.toSec() <= link_delay_s_) return frames_.lookup(link, error);
  return frames_.lookupAt(link, now - ros::Duration(link_delay_s_), error);
}

bool NodeObstacles::update(const ros::Time& now) {
  std::optional<std::vector<core::PlacedShape>> obstacles =
      obstacles_.place([this, &now](const std::string& link) {
        std::string error;
        const std::optional<Eigen::Isometry3d> pose = linkPose(link, now, &error);
        if (!pose) {
          ROS_WARN_THROTTLE(5.0, "obstacle link '%s' is not in tf (%s)", link.c_str(),
                            error.c_str());
        }
        return pose;
      });
  if (!obstacles) return false;
  if (*obstacles != applied_) {  // recorded (and applied) only when tf moved one
    try {
      apply_(core::SetObstaclesCommand{*obstacles});
      applied_ = std::move(*obstacles);
    } catch (const core::CommandError& e) {
      ROS_WARN_THROTTLE(1.0, "obstacles not moved: %s", e.what());
    }
  }
  return true;
}

}  // namespace deformable_sim::ros_layer
