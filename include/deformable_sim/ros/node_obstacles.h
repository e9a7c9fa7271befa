// The obstacles the node keeps in its simulation: the scene's own, and the collision shapes of the
// robot links it names, placed before every tick where tf had the links ~link_delay earlier
// (interpolated, so they move smoothly however often joint states come). They are drawn on the
// latched ~obstacles whenever one of them appears, goes or moves.
#pragma once

#include <ros/ros.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "deformable_sim/core/driver/linked_obstacles.h"
#include "deformable_sim/core/session/session.h"
#include "deformable_sim/ros/frame_resolver.h"
#include "deformable_sim/ros/node_parameters.h"
#include "deformable_sim/ros/robot_links.h"

namespace deformable_sim::ros_layer {

class NodeObstacles {
 public:
  using Apply = std::function<int(const core::SessionCommand&)>;

  /// The obstacles of `params`' scene, placed ~link_delay late and drawn in ~world_frame on
  /// ~obstacles of `private_node`. Throws std::runtime_error (urdf.links: ...) when a link's
  /// shapes cannot be had.
  NodeObstacles(const NodeParameters& params, RobotLinks& links, const FrameResolver& frames,
                Apply apply, ros::NodeHandle& private_node);

  /// Places the obstacles for the tick at `now`, and applies (and so records) them and draws them
  /// on ~obstacles when tf moved one. False while tf has not yet placed every link: the node must
  /// not step then.
  bool update(const ros::Time& now);
  /// Where tf had `link` ~link_delay before `now` (the latest, early on); nullopt with `error`
  /// set when it has no pose.
  std::optional<Eigen::Isometry3d> linkPose(const std::string& link, const ros::Time& now,
                                            std::string* error) const;
  /// After a reset: the next update applies the obstacles again.
  void forget() { applied_.clear(); }

 private:
  void draw(const std::vector<core::PlacedShape>& obstacles);

  const FrameResolver& frames_;
  double link_delay_s_;
  Apply apply_;
  core::LinkedObstacles obstacles_;
  std::vector<core::PlacedShape> applied_;  ///< as last applied
  std::string world_frame_;
  std::vector<std::string>
      links_;                   ///< the robot links among the obstacles (their markers' namespace)
  ros::Publisher markers_pub_;  ///< ~obstacles
  std::vector<core::PlacedShape> drawn_;  ///< as last published on ~obstacles
  bool drawn_once_ = false;               ///< something was published (an empty set, perhaps)
};

}  // namespace deformable_sim::ros_layer
