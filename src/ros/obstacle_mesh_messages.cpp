#include "deformable_sim/ros/obstacle_mesh_messages.h"

#include <stdexcept>

#include "deformable_sim/core/session/commands.h"

namespace deformable_sim::ros_layer {

ObstacleMesh toMessage(const std::string& id, const core::TriangleMeshShape& mesh) {
  ObstacleMesh m;
  m.id = id;
  core::flatten(mesh.mesh(), m.vertices, m.triangles);
  m.open_depth = mesh.openDepth();
  return m;
}

core::MeshCatalogue::Mesh fromMessage(const ObstacleMesh& m) {
  const std::string what = "obstacle mesh '" + m.id + "'";
  try {
    return std::make_shared<const core::TriangleMeshShape>(
        core::unflatten(m.vertices, m.triangles, what), m.open_depth);
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    throw core::CommandError(message.rfind(what, 0) == 0 ? message : what + ": " + message);
  }
}

void receive(const std::vector<ObstacleMesh>& meshes, core::MeshCatalogue& catalogue) {
  for (const ObstacleMesh& m : meshes) {
    if (!catalogue.knows(m.id)) catalogue.addRecorded(m.id, fromMessage(m));
  }
}

void markRecorded(const std::vector<ObstacleMesh>& meshes, core::MeshCatalogue& catalogue) {
  for (const ObstacleMesh& m : meshes) catalogue.markRecorded(m.id);
}

}  // namespace deformable_sim::ros_layer
