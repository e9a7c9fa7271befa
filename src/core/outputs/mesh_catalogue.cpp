#include "deformable_sim/core/outputs/mesh_catalogue.h"

#include <algorithm>

#include "deformable_sim/core/session/commands.h"

namespace deformable_sim::core {

void MeshCatalogue::addRecorded(const std::string& id, const Mesh& mesh) {
  if (meshes_.emplace(id, mesh).second) ids_.emplace(mesh.get(), id);
  recorded_.insert(id);
}

std::string MeshCatalogue::idFor(const Mesh& mesh, std::vector<Entry>& unrecorded) {
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
  const bool listed = std::any_of(unrecorded.begin(), unrecorded.end(),
                                  [&id](const Entry& e) { return e.id == id; });
  if (recorded_.count(id) == 0 && !listed) unrecorded.push_back({id, mesh});
  return id;
}

const MeshCatalogue::Mesh& MeshCatalogue::find(const std::string& id) const {
  const auto found = meshes_.find(id);
  if (found == meshes_.end()) {
    throw CommandError("obstacle mesh '" + id + "' was not recorded before its use");
  }
  return found->second;
}

}  // namespace deformable_sim::core
