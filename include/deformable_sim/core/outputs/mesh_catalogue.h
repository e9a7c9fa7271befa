// The triangle meshes of a session's obstacles and grasp regions under the ids its records give
// them, so that each mesh's triangles are recorded once and named by id afterwards. The node and
// a replay each keep one for the whole session.
#pragma once

#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "deformable_sim/core/geometry/triangle_mesh_shape.h"

namespace deformable_sim::core {

class MeshCatalogue {
 public:
  using Mesh = std::shared_ptr<const TriangleMeshShape>;
  struct Entry {
    std::string id;
    Mesh mesh;
  };

  /// Keeps `mesh` under `id` as recorded already (the scene's record carries it). An id known
  /// already keeps its mesh: a record read back by the one who wrote it names its own meshes.
  void addRecorded(const std::string& id, const Mesh& mesh);
  /// The id of `mesh`, given now if it has none; while its triangles are not recorded yet, it is
  /// appended to `unrecorded` (once).
  std::string idFor(const Mesh& mesh, std::vector<Entry>& unrecorded);
  /// Once a record that carries the mesh `id` is out: it need not be sent again.
  void markRecorded(const std::string& id) { recorded_.insert(id); }
  bool knows(const std::string& id) const { return meshes_.count(id) > 0; }
  /// The mesh of `id`; throws CommandError when no record carried it.
  const Mesh& find(const std::string& id) const;

 private:
  std::map<const TriangleMeshShape*, std::string> ids_;
  std::map<std::string, Mesh> meshes_;
  std::set<std::string> recorded_;
  int next_id_ = 0;
};

}  // namespace deformable_sim::core
