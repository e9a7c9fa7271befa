// The robot's links as the node sees them: their collision shapes, read once from the robot
// description (the scene's urdf.file, else the robot_description parameter), posed by tf. They
// are the obstacles a scene names (urdf.links) and the regions of REGION_LINK grasps.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "deformable_sim/core/scene.h"
#include "deformable_sim/core/shape.h"
#include "deformable_sim/ros/frame_resolver.h"

namespace deformable_sim::ros_layer {

class RobotLinks {
 public:
  /// `urdf_file`: the scene's urdf.file; empty: the robot_description parameter.
  explicit RobotLinks(std::string urdf_file) : urdf_file_(std::move(urdf_file)) {}

  /// The link's collision shapes in its own frame. Throws core::CommandError naming the problem
  /// when there is no valid robot description or the link has no usable shape.
  const std::vector<core::PlacedShape>& shapes(const std::string& link);

 private:
  void load();

  std::string urdf_file_;
  bool loaded_ = false;
  std::map<std::string, std::vector<core::PlacedShape>> shapes_;  ///< link -> shapes
};

/// The scene's obstacles: its own fixed ones and those of the robot links it names, posed by tf.
class LinkObstacles {
 public:
  /// Throws std::runtime_error (urdf.links: ...) when a link's shapes cannot be had.
  LinkObstacles(const core::SceneSpec& scene, RobotLinks& links);

  /// Every obstacle in the world as tf has the links now (a link tf lost keeps its last pose);
  /// nullopt while tf has not yet placed every link.
  std::optional<std::vector<core::PlacedShape>> place(const FrameResolver& frames);

 private:
  struct Placed {
    std::string link;
    core::PlacedShape local;                  ///< pose in the link's frame
    std::optional<core::PlacedShape> placed;  ///< in the world, once tf had the link
  };
  std::vector<core::PlacedShape> fixed_;
  std::vector<Placed> linked_;
};

}  // namespace deformable_sim::ros_layer
