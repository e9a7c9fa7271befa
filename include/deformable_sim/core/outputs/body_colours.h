// The colour each body is drawn in: its scene entry's own, or a fixed palette's by body index, so
// that bodies side by side can be told apart and keep their colours from run to run.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "deformable_sim/core/session/scene.h"

namespace deformable_sim::core {

/// The palette's colour of the `index`th body (red, green, blue in [0, 1]); the palette repeats
/// after its last colour.
Eigen::Vector3d paletteColour(int index);

/// For each body of `scene`, in order: its `colour`, or paletteColour of its index.
std::vector<Eigen::Vector3d> bodyColours(const SceneSpec& scene);

}  // namespace deformable_sim::core
