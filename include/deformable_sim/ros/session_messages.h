// Between the core's session commands and the messages that record them (~applied), and between
// a scene with its meshes and the ~scene message. The node applies a command only as it reads
// back from its message, so that a replay of the recorded messages repeats it exactly. Mesh
// obstacles travel by id: their triangles go once into the message that first needs them
// (through the catalogue, which the node and a replay each keep for the whole session).
#pragma once

#include <string>
#include <vector>

#include "deformable_sim/Applied.h"
#include "deformable_sim/Scene.h"
#include "deformable_sim/core/elements/mesh.h"
#include "deformable_sim/core/geometry/shape.h"
#include "deformable_sim/core/outputs/mesh_catalogue.h"
#include "deformable_sim/core/session/session.h"

namespace deformable_sim::ros_layer {

/// A mesh that `catalogue` has not recorded yet goes into the message's `meshes`; once the
/// message is published, markRecorded(message.meshes, catalogue).
Applied toMessage(const core::SessionCommand& command, core::MeshCatalogue& catalogue);
/// Throws core::CommandError for an unknown kind or shape code, or a mesh id that no message
/// (this one, an earlier one, the scene) carried.
core::SessionCommand fromMessage(const Applied& message, core::MeshCatalogue& catalogue);

/// The scene (its file's text and path, or empty for the built-in one), the node's step, every
/// body's mesh (with the surface it was made from, if any: `surfaces` may be shorter), and the
/// triangles of the meshes among the scene's `obstacles` (recorded in `catalogue` under
/// io::sceneObstacleKey(k)) and its obstacle links' `link_shapes` (so that a bag whose recording
/// starts late still holds them).
Scene toSceneMessage(const std::string& path, const std::string& yaml, double dt, int substeps,
                     const std::vector<core::Mesh>& meshes,
                     const std::vector<std::optional<core::EmbeddedSurface>>& surfaces,
                     const std::vector<std::string>& body_names,
                     const std::vector<core::PlacedShape>& obstacles,
                     const std::vector<core::PlacedShape>& link_shapes,
                     core::MeshCatalogue& catalogue);
/// The meshes of a ~scene message and, in `surfaces` (one per mesh) if given, the surfaces bodies
/// were made from. Throws std::invalid_argument when the arrays do not fit.
std::vector<core::Mesh> meshesFromMessage(
    const Scene& message, std::vector<std::optional<core::EmbeddedSurface>>* surfaces = nullptr);

}  // namespace deformable_sim::ros_layer
