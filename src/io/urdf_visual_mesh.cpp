#include "deformable_sim/io/urdf_visual_mesh.h"

#include <urdf_parser/urdf_parser.h>

#include <Eigen/Geometry>
#include <filesystem>

#include "urdf_pose.h"

namespace deformable_sim::io {

namespace {

// Appends the mesh of `geometry`, posed by `pose`, to `surface`.
void appendMesh(const urdf::Mesh& geometry, const Eigen::Isometry3d& pose,
                const PackageResolver& resolver, const std::string& base_directory,
                core::TriangleMesh& surface) {
  std::filesystem::path path = resolveMeshUri(geometry.filename, resolver);
  if (path.is_relative() && !base_directory.empty()) path = base_directory / path;
  const Eigen::Vector3d scale(geometry.scale.x, geometry.scale.y, geometry.scale.z);
  const core::TriangleMesh part = readTriangleMesh(path.lexically_normal().string(), scale);
  const int offset = static_cast<int>(surface.vertices.size());
  for (const Eigen::Vector3d& v : part.vertices) surface.vertices.push_back(pose * v);
  for (const Eigen::Vector3i& t : part.triangles) surface.triangles.push_back(t.array() + offset);
}

}  // namespace

core::TriangleMesh readVisualMesh(const std::string& urdf_xml, const std::string& link,
                                  const PackageResolver& resolver,
                                  const std::string& base_directory) {
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(urdf_xml);
  if (!model) throw UrdfError("the robot description is not a valid URDF");
  const auto found = model->links_.find(link);
  if (found == model->links_.end()) {
    throw UrdfError("no link '" + link + "' in the robot description");
  }
  core::TriangleMesh surface;
  for (const urdf::VisualSharedPtr& visual : found->second->visual_array) {
    if (!visual || !visual->geometry || visual->geometry->type != urdf::Geometry::MESH) continue;
    appendMesh(static_cast<const urdf::Mesh&>(*visual->geometry), toIsometry(visual->origin),
               resolver, base_directory, surface);
  }
  if (surface.triangles.empty()) {
    throw UrdfError("link '" + link + "' has no visual mesh to make a body of");
  }
  return surface;
}

}  // namespace deformable_sim::io
