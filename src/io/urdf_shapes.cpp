#include "deformable_sim/io/urdf_shapes.h"

#include <urdf_parser/urdf_parser.h>

#include <filesystem>
#include <memory>

#include "urdf_pose.h"

namespace deformable_sim::io {

namespace {

// Reads a <mesh> element into `shape`; false (with a warning) when it cannot be read.
bool readMeshShape(const urdf::Mesh& mesh, const std::string& link, const PackageResolver& resolver,
                   const std::string& base_directory, core::Shape& shape,
                   std::vector<std::string>* warnings) {
  try {
    std::filesystem::path path = resolveMeshUri(mesh.filename, resolver);
    if (path.is_relative() && !base_directory.empty()) path = base_directory / path;
    const Eigen::Vector3d scale(mesh.scale.x, mesh.scale.y, mesh.scale.z);
    try {
      shape.mesh = std::make_shared<const core::TriangleMeshShape>(
          readTriangleMesh(path.lexically_normal().string(), scale));
      shape.mesh_uri = meshResourceUri(mesh.filename, path.lexically_normal().string());
      shape.mesh_scale = scale;
    } catch (const std::invalid_argument& e) {
      throw TriangleMeshError("mesh file '" + path.string() + "': " + e.what());
    }
  } catch (const TriangleMeshError& e) {
    if (warnings) {
      warnings->push_back("link '" + link + "': collision mesh '" + mesh.filename +
                          "' is not used: " + e.what());
    }
    return false;
  }
  shape.kind = core::Shape::Kind::kMesh;
  return true;
}

// The shape of a <geometry>; false for one that is not used (a mesh that cannot be read, with a
// warning).
bool readGeometry(const urdf::Geometry& geometry, const std::string& link,
                  const PackageResolver& resolver, const std::string& base_directory,
                  core::Shape& shape, std::vector<std::string>* warnings) {
  switch (geometry.type) {
    case urdf::Geometry::BOX: {
      const auto& box = static_cast<const urdf::Box&>(geometry);
      shape.kind = core::Shape::Kind::kBox;
      shape.size << box.dim.x, box.dim.y, box.dim.z;
      return true;
    }
    case urdf::Geometry::SPHERE:
      shape.kind = core::Shape::Kind::kSphere;
      shape.radius = static_cast<const urdf::Sphere&>(geometry).radius;
      return true;
    case urdf::Geometry::CYLINDER: {
      const auto& cylinder = static_cast<const urdf::Cylinder&>(geometry);
      shape.kind = core::Shape::Kind::kCylinder;
      shape.radius = cylinder.radius;
      shape.length = cylinder.length;
      return true;
    }
    case urdf::Geometry::MESH:
      return readMeshShape(static_cast<const urdf::Mesh&>(geometry), link, resolver, base_directory,
                           shape, warnings);
  }
  return false;
}

}  // namespace

std::map<std::string, std::vector<core::PlacedShape>> readCollisionShapes(
    const std::string& urdf_xml, std::vector<std::string>* warnings,
    const PackageResolver& resolver, const std::string& base_directory) {
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(urdf_xml);
  if (!model) throw UrdfError("the robot description is not a valid URDF");
  std::map<std::string, std::vector<core::PlacedShape>> shapes;
  for (const auto& [name, link] : model->links_) {
    std::vector<core::PlacedShape>& placed = shapes[name];
    for (const urdf::CollisionSharedPtr& collision : link->collision_array) {
      if (!collision || !collision->geometry) continue;
      core::PlacedShape shape;
      shape.name = name;
      shape.pose = toIsometry(collision->origin);
      if (!readGeometry(*collision->geometry, name, resolver, base_directory, shape.shape,
                        warnings)) {
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
    throw UrdfError("link '" + link +
                    "' has no collision geometry that could be read (box, sphere, cylinder or "
                    "mesh)");
  }
  return found->second;
}

}  // namespace deformable_sim::io
