#include "deformable_sim/io/urdf_shapes.h"

#include <urdf_parser/urdf_parser.h>

namespace deformable_sim::io {

namespace {

Eigen::Isometry3d toPose(const urdf::Pose& pose) {
  Eigen::Isometry3d result = Eigen::Isometry3d::Identity();
  result.translation() << pose.position.x, pose.position.y, pose.position.z;
  result.linear() =
      Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
          .normalized()
          .toRotationMatrix();
  return result;
}

}  // namespace

std::map<std::string, std::vector<core::PlacedShape>> readCollisionShapes(
    const std::string& urdf_xml, std::vector<std::string>* warnings) {
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(urdf_xml);
  if (!model) throw UrdfError("the robot description is not a valid URDF");
  std::map<std::string, std::vector<core::PlacedShape>> shapes;
  for (const auto& [name, link] : model->links_) {
    std::vector<core::PlacedShape>& placed = shapes[name];
    for (const urdf::CollisionSharedPtr& collision : link->collision_array) {
      if (!collision || !collision->geometry) continue;
      core::PlacedShape shape;
      shape.name = name;
      shape.pose = toPose(collision->origin);
      switch (collision->geometry->type) {
        case urdf::Geometry::BOX: {
          const auto& box = static_cast<const urdf::Box&>(*collision->geometry);
          shape.shape.kind = core::Shape::Kind::kBox;
          shape.shape.size << box.dim.x, box.dim.y, box.dim.z;
          break;
        }
        case urdf::Geometry::SPHERE:
          shape.shape.kind = core::Shape::Kind::kSphere;
          shape.shape.radius = static_cast<const urdf::Sphere&>(*collision->geometry).radius;
          break;
        case urdf::Geometry::CYLINDER: {
          const auto& cylinder = static_cast<const urdf::Cylinder&>(*collision->geometry);
          shape.shape.kind = core::Shape::Kind::kCylinder;
          shape.shape.radius = cylinder.radius;
          shape.shape.length = cylinder.length;
          break;
        }
        default:
          if (warnings) {
            warnings->push_back("link '" + name +
                                "': mesh collision geometry is not used (boxes, spheres and "
                                "cylinders are)");
          }
          continue;
      }
      try {
        core::validate(shape.shape, "link '" + name + "' collision");
      } catch (const std::invalid_argument& e) {
        throw UrdfError(e.what());
      }
      placed.push_back(shape);
    }
  }
  return shapes;
}

const std::vector<core::PlacedShape>& linkShapes(
    const std::map<std::string, std::vector<core::PlacedShape>>& shapes, const std::string& link) {
  const auto found = shapes.find(link);
  if (found == shapes.end()) {
    std::string known;
    for (const auto& [name, placed] : shapes) known += (known.empty() ? "" : ", ") + name;
    throw UrdfError("no link '" + link + "' in the robot description (links: " + known + ")");
  }
  if (found->second.empty()) {
    throw UrdfError("link '" + link + "' has no box, sphere or cylinder collision geometry");
  }
  return found->second;
}

}  // namespace deformable_sim::io
