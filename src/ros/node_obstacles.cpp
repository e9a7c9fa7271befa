#include "deformable_sim/ros/node_obstacles.h"

#include <ros/console.h>
#include <visualization_msgs/MarkerArray.h>

#include <utility>

#include "deformable_sim/ros/obstacle_markers.h"

namespace deformable_sim::ros_layer {

NodeObstacles::NodeObstacles(const NodeParameters& params, RobotLinks& links,
                             const FrameResolver& frames, Apply apply,
                             ros::NodeHandle& private_node)
    : frames_(frames),
      link_delay_s_(params.link_delay_s),
      apply_(std::move(apply)),
      obstacles_(sceneObstacles(params.scene, links)),
      world_frame_(params.world_frame),
      links_(params.scene.urdf_links) {
  markers_pub_ = private_node.advertise<visualization_msgs::MarkerArray>("obstacles", 1, true);
}

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
  if (!drawn_once_ || *obstacles != drawn_) draw(*obstacles);
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

void NodeObstacles::draw(const std::vector<core::PlacedShape>& obstacles) {
  std_msgs::Header header;
  header.frame_id = world_frame_;  // no stamp: a late subscriber places them with the latest tf
  markers_pub_.publish(obstacleMarkers(obstacles, header, links_));
  drawn_ = obstacles;
  drawn_once_ = true;
}

}  // namespace deformable_sim::ros_layer
