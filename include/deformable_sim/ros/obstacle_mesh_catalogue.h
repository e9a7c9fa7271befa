// The meshes of a session's obstacles and grasp regions under the ids its messages give them, so
// that each mesh's triangles are recorded once (ObstacleMesh) and named by id afterwards.
#pragma once

#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "deformable_sim/ObstacleMesh.h"
#include "deformable_sim/core/triangle_mesh_shape.h"

namespace deformable_sim::ros_layer {

ObstacleMesh toMessage(const std::string& id, const core::TriangleMeshShape& mesh);
/// Throws core::CommandError naming the mesh when its arrays do not make a valid mesh.
std::shared_ptr<const core::TriangleMeshShape> fromMessage(const ObstacleMesh& message);

class ObstacleMeshCatalogue {
 public:
  using Mesh = std::shared_ptr<const core::TriangleMeshShape>;

  /// Keeps `mesh` under `id` as already recorded (a ~scene message carries it).
  void addRecorded(const std::string& id, const Mesh& mesh);
  /// The id of `mesh`, given now if it has none; while its triangles are not recorded yet, they
  /// are appended to `unrecorded` (once per call).
  std::string idFor(const Mesh& mesh, std::vector<ObstacleMesh>& unrecorded);
  /// Once a message that carries `meshes` is published: they need not be sent again.
  void markRecorded(const std::vector<ObstacleMesh>& meshes);
  /// Keeps the meshes that a message carries, under their ids (those known already stay as they
  /// are). Throws core::CommandError for invalid arrays.
  void receive(const std::vector<ObstacleMesh>& meshes);
  /// The mesh of `id`; throws core::CommandError when no message carried it.
  const Mesh& find(const std::string& id) const;

 private:
  std::map<const core::TriangleMeshShape*, std::string> ids_;
  std::map<std::string, Mesh> meshes_;
  std::set<std::string> recorded_;
  int next_id_ = 0;
};

}  // namespace deformable_sim::ros_layer
