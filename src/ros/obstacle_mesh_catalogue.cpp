#include "deformable_sim/ros/obstacle_mesh_catalogue.h"

#include <stdexcept>

#include "deformable_sim/core/commands.h"

namespace deformable_sim::ros_layer {

ObstacleMesh toMessage(const std::string& id, const core::TriangleMeshShape& mesh) {
  ObstacleMesh m;
  m.id = id;
  for (const Eigen::Vector3d& v : mesh.mesh().vertices)
    m.vertices.insert(m.vertices.end(), {v.x(), v.y(), v.z()});
  for (const Eigen::Vector3i& t : mesh.mesh().triangles) {
    for (int c = 0; c < 3; ++c) m.triangles.push_back(static_cast<uint32_t>(t[c]));
  }
  m.open_depth = mesh.openDepth();
  return m;
}

std::shared_ptr<const core::TriangleMeshShape> fromMessage(const ObstacleMesh& m) {
  if (m.vertices.size() % 3 != 0 || m.triangles.size() % 3 != 0) {
    throw core::CommandError("obstacle mesh '" + m.id +
                             "': vertices and triangles must come in threes");
  }
  core::TriangleMesh mesh;
  for (size_t k = 0; k < m.vertices.size(); k += 3) {
    mesh.vertices.emplace_back(m.vertices[k], m.vertices[k + 1], m.vertices[k + 2]);
  }
  for (size_t k = 0; k < m.triangles.size(); k += 3) {
    // Indices past int's range become negative and are rejected as out of range.
    mesh.triangles.emplace_back(static_cast<int>(m.triangles[k]),
                                static_cast<int>(m.triangles[k + 1]),
                                static_cast<int>(m.triangles[k + 2]));
  }
  try {
    return std::make_shared<const core::TriangleMeshShape>(std::move(mesh), m.open_depth);
  } catch (const std::invalid_argument& e) {
    throw core::CommandError("obstacle mesh '" + m.id + "': " + e.what());
  }
}

void ObstacleMeshCatalogue::addRecorded(const std::string& id, const Mesh& mesh) {
  ids_.emplace(mesh.get(), id);
  meshes_.emplace(id, mesh);
  recorded_.insert(id);
}

std::string ObstacleMeshCatalogue::idFor(const Mesh& mesh, std::vector<ObstacleMesh>& unrecorded) {
  auto found = ids_.find(mesh.get());
  if (found == ids_.end()) {
    std::string id;
    do {
      id = "mesh" + std::to_string(next_id_++);
    } while (meshes_.count(id) > 0);
    found = ids_.emplace(mesh.get(), id).first;
    meshes_.emplace(id, mesh);
  }
  const std::string& id = found->second;
  if (recorded_.count(id) == 0) {
    bool listed = false;
    for (const ObstacleMesh& m : unrecorded) listed = listed || m.id == id;
    if (!listed) unrecorded.push_back(toMessage(id, *mesh));
  }
  return id;
}

void ObstacleMeshCatalogue::markRecorded(const std::vector<ObstacleMesh>& meshes) {
  for (const ObstacleMesh& m : meshes) recorded_.insert(m.id);
}

void ObstacleMeshCatalogue::receive(const std::vector<ObstacleMesh>& meshes) {
  for (const ObstacleMesh& m : meshes) {
    if (meshes_.count(m.id) > 0) continue;  // the node reading back its own message
    const Mesh mesh = fromMessage(m);
    ids_.emplace(mesh.get(), m.id);
    meshes_.emplace(m.id, mesh);
    recorded_.insert(m.id);
  }
}

const ObstacleMeshCatalogue::Mesh& ObstacleMeshCatalogue::find(const std::string& id) const {
  const auto found = meshes_.find(id);
  if (found == meshes_.end()) {
    throw core::CommandError("obstacle mesh '" + id + "' was not recorded before its use");
  }
  return found->second;
}

}  // namespace deformable_sim::ros_layer
