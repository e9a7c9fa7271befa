// Between the core's session commands and the messages that record them (~applied), and between
// a scene with its meshes and the ~scene message. The node applies a command only as it reads
// back from its message, so that a replay of the recorded messages repeats it exactly.
#pragma once

#include <string>
#include <vector>

#include "deformable_sim/Applied.h"
#include "deformable_sim/Scene.h"
#include "deformable_sim/core/mesh.h"
#include "deformable_sim/core/session.h"

namespace deformable_sim::ros_layer {

Applied toMessage(const core::SessionCommand& command);
/// Throws core::CommandError for an unknown kind or shape code.
core::SessionCommand fromMessage(const Applied& message);

/// The scene (its file's text and path, or empty for the built-in one), the node's step and
/// every body's mesh.
Scene toSceneMessage(const std::string& path, const std::string& yaml, double dt, int substeps,
                     const std::vector<core::Mesh>& meshes,
                     const std::vector<std::string>& body_names);
/// The meshes of a ~scene message. Throws std::invalid_argument when the arrays do not fit.
std::vector<core::Mesh> meshesFromMessage(const Scene& message);

}  // namespace deformable_sim::ros_layer
