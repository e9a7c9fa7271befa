#include "deformable_sim/ros/robot_links.h"

#include <ros/console.h>
#include <ros/node_handle.h>
#include <ros/package.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "deformable_sim/io/urdf_shapes.h"

namespace deformable_sim::ros_layer {

namespace {

// package://pkg/rest -> <pkg's directory>/rest, "" when ROS knows no such package.
std::string packagePath(const std::string& uri) {
  const std::string rest = uri.substr(std::string("package://").size());
  const size_t slash = rest.find('/');
  const std::string directory = ros::package::getPath(rest.substr(0, slash));
  if (directory.empty()) return "";
  return slash == std::string::npos ? directory : directory + rest.substr(slash);
}

}  // namespace

io::SurfaceSources surfaceSources(const core::SceneSpec& scene) {
  io::SurfaceSources sources;
  sources.resolver = packagePath;
  if (scene.urdf_file.empty())
    ros::NodeHandle().getParam("robot_description", sources.robot_description);
  return sources;
}

const std::vector<core::PlacedShape>& RobotLinks::shapes(const std::string& link) {
  load();
  try {
    return io::linkShapes(shapes_, link);
  } catch (const io::UrdfError& e) {
    throw core::CommandError(e.what());
  }
}

std::vector<core::PlacedShape> RobotLinks::shapes(const std::vector<std::string>& links) {
  std::vector<core::PlacedShape> all;
  for (const std::string& link : links) {
    const std::vector<core::PlacedShape>& mine = shapes(link);
    all.insert(all.end(), mine.begin(), mine.end());
  }
  return all;
}

void RobotLinks::load() {
  if (loaded_) return;
  std::string xml;
  if (!urdf_file_.empty()) {
    std::ifstream file(urdf_file_);
    if (!file) throw core::CommandError(urdf_file_ + ": cannot open the URDF file");
    std::stringstream text;
    text << file.rdbuf();
    xml = text.str();
  } else if (!ros::NodeHandle().getParam("robot_description", xml) || xml.empty()) {
    throw core::CommandError(
        "no robot description: set the robot_description parameter or the scene's urdf.file");
  }
  std::vector<std::string> warnings;
  try {
    // Relative mesh file names: against the URDF file's directory, or the working directory.
    const std::string base = std::filesystem::path(urdf_file_).parent_path().string();
    shapes_ = io::readCollisionShapes(xml, &warnings, packagePath, base);
  } catch (const io::UrdfError& e) {
    throw core::CommandError(e.what());
  }
  for (const std::string& w : warnings) ROS_WARN("%s", w.c_str());
  loaded_ = true;
}

core::LinkedObstacles sceneObstacles(const core::SceneSpec& scene, RobotLinks& links) {
  core::LinkedObstacles obstacles(scene.obstacles);
  for (const std::string& link : scene.urdf_links) {
    try {
      for (const core::PlacedShape& shape : links.shapes(link)) obstacles.attach(link, shape);
    } catch (const core::CommandError& e) {
      throw std::runtime_error(std::string("urdf.links: ") + e.what());
    }
  }
  return obstacles;
}

}  // namespace deformable_sim::ros_layer
