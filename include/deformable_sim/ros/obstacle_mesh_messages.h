// A triangle mesh of an obstacle or grasp region as the ObstacleMesh message that records it once
// (core::MeshCatalogue gives it its id), and back.
#pragma once

#include <string>
#include <vector>

#include "deformable_sim/ObstacleMesh.h"
#include "deformable_sim/core/outputs/mesh_catalogue.h"

namespace deformable_sim::ros_layer {

ObstacleMesh toMessage(const std::string& id, const core::TriangleMeshShape& mesh);
/// Throws core::CommandError naming the mesh when its arrays do not make a valid mesh.
core::MeshCatalogue::Mesh fromMessage(const ObstacleMesh& message);

/// Keeps the meshes that a message carries in `catalogue`, under their ids. Throws
/// core::CommandError for invalid arrays.
void receive(const std::vector<ObstacleMesh>& meshes, core::MeshCatalogue& catalogue);
/// Once a message that carries `meshes` is published: they need not be sent again.
void markRecorded(const std::vector<ObstacleMesh>& meshes, core::MeshCatalogue& catalogue);

}  // namespace deformable_sim::ros_layer
