// A session recorded in a bag (the node's latched ~scene, its log ~applied and its ~state), read
// into the core's types for a re-simulation.
#pragma once

#include <std_msgs/Header.h>

#include <string>
#include <vector>

#include "deformable_sim/Scene.h"
#include "deformable_sim/core/session/resimulation.h"

namespace deformable_sim::ros_layer {

/// When the node applied a command: an ~applied message's header, episode and step.
struct AppliedStamp {
  std_msgs::Header header;
  long episode = 0;
  long step = 0;
};

struct RecordedSession {
  std::string node;  ///< whose session it is, e.g. /deformable_sim
  Scene scene;       ///< the first ~scene message
  core::Recording recording;
  /// The header of every recorded state; a state's `source` is its index here.
  std::vector<std_msgs::Header> state_headers;
  /// ~applied messages of a kind this build does not know: the re-simulation refuses them.
  long unknown_commands = 0;
  std::vector<AppliedStamp> applied_stamps;  ///< every ~applied message's, in the bag's order
};

/// Reads the session of `node` (empty: the bag's only node) from the bag at `path`. Throws
/// ReplayError naming the problem: a bag that cannot be read (truncated, not a bag), one without
/// a recorded scene, several nodes and none chosen, messages of another version. Without
/// `scene_required` a bag with no ~scene is read too (its node found by ~applied; `scene` stays
/// empty): the scene then comes from a file.
RecordedSession readRecordedSession(const std::string& path, const std::string& node,
                                    bool scene_required = true);

/// The recorded scene as the node read it (its file's text, or the built-in scene) at the node's
/// step, mesh obstacles from their recorded triangles. Throws ReplayError.
core::SceneSpec recordedSceneSpec(const Scene& scene);

}  // namespace deformable_sim::ros_layer
