// The robot's links as the node sees them: their collision shapes, read once from the robot
// description (the scene's urdf.file, else the robot_description parameter). They are the
// obstacles a scene names (urdf.links) and the regions of REGION_LINK grasps.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "deformable_sim/core/driver/linked_obstacles.h"
#include "deformable_sim/core/geometry/shape.h"
#include "deformable_sim/core/session/commands.h"
#include "deformable_sim/core/session/scene.h"
#include "deformable_sim/io/scene_file.h"

namespace deformable_sim::ros_layer {

class RobotLinks {
 public:
  /// `urdf_file`: the scene's urdf.file; empty: the robot_description parameter.
  explicit RobotLinks(std::string urdf_file) : urdf_file_(std::move(urdf_file)) {}

  /// The link's collision shapes in its own frame. Throws core::CommandError naming the problem
  /// when there is no valid robot description or the link has no usable shape.
  const std::vector<core::PlacedShape>& shapes(const std::string& link);
  /// The shapes of every link named, in order.
  std::vector<core::PlacedShape> shapes(const std::vector<std::string>& links);

 private:
  void load();

  std::string urdf_file_;
  bool loaded_ = false;
  std::map<std::string, std::vector<core::PlacedShape>> shapes_;  ///< link -> shapes
};

/// Where the scene's bodies made from surfaces find package:// files (ROS's package paths) and
/// a urdf_link's robot description (the scene's urdf.file, else the robot_description
/// parameter).
io::SurfaceSources surfaceSources(const core::SceneSpec& scene);

/// The scene's obstacles with those of the robot links it names (urdf.links), in their links'
/// frames. Throws std::runtime_error (urdf.links: ...) when a link's shapes cannot be had.
core::LinkedObstacles sceneObstacles(const core::SceneSpec& scene, RobotLinks& links);

}  // namespace deformable_sim::ros_layer
