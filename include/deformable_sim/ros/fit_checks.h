// Whether a fit's inputs belong together, checked before any time is spent fitting: a scene file
// other than the bag's would re-simulate another session (its commands dropped, its motion
// another's), and a wrench compared with a grasp or a link the session never had would be
// compared with zero. Each throws identify::FitSpecError naming the difference.
#pragma once

#include <vector>

#include "deformable_sim/core/session/resimulation.h"
#include "deformable_sim/identify/fit_spec.h"
#include "deformable_sim/ros/recorded_session.h"

namespace deformable_sim::ros_layer {

/// `spec` and `meshes` (a scene file's) against the bag's: every body its log commands, and,
/// where the bag holds ~scene, the same dt and each body's number of nodes.
void checkSceneIsTheBags(const RecordedSession& session, const core::SceneSpec& spec,
                         const std::vector<core::Mesh>& meshes);

/// Every grasp: and link: of the fit's observations in the log (grasps; obstacles the node set)
/// or the scene (obstacles).
void checkSourcesAppear(const identify::FitSpec& fit, const core::Recording& recording,
                        const core::SceneSpec& spec);

}  // namespace deformable_sim::ros_layer
