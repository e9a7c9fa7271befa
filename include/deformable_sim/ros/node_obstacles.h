// The obstacles the node keeps in its simulation: the scene's own, and the collision shapes of the
// robot links it names, placed before every tick where tf had the links ~link_delay earlier
// (interpolated, so they move smoothly however often joint states come).
#pragma once

#include <ros/time.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "deformable_sim/core/linked_obstacles.h"
#include "deformable_sim/core/session.h"
#include "deformable_sim/ros/frame_resolver.h"
#include "deformable_sim/ros/robot_links.h"

namespace deformable_sim::ros_layer {

class NodeObstacles {
 public:
  using Apply = std::function<int(const core::SessionCommand&)>;

  /// Throws std::runtime_error (urdf.links: ...) when a link's shapes cannot be had.
  NodeObstacles(const core::SceneSpec& scene, RobotLinks& links, const FrameResolver& frames,
                double link_delay_s, Apply apply);

  /// Places the obstacles for the tick at `now`, and applies (and so records) them when tf moved
  /// one. False while tf has not yet placed every link: the node must not step then.
  bool update(const ros::Time& now);
  /// Where tf had `link` ~link_delay before `now` (the latest, early on); nullopt with `error`
  /// set when it has no pose.
  std::optional<Eigen::Isometry3d> linkPose(const std::string& link, const ros::Time& now,
                                            std::string* error) const;
  /// After a reset: the next update applies the obstacles again.
  void forget() { applied_.clear(); }

 private:
  const FrameResolver& frames_;
  double link_delay_s_;
  Apply apply_;
  core::LinkedObstacles obstacles_;
  std::vector<core::PlacedShape> applied_;  ///< as last applied
};

}  // namespace deformable_sim::ros_layer
