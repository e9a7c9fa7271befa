// The built-in scene: what the node simulates when it is given no scene file.
#pragma once

#include "deformable_sim/core/session/scene.h"

namespace deformable_sim::core {

/// A soft foam cantilever, 0.5 m x 0.1 m x 0.1 m (E = 100 kPa, ν = 0.3, ρ = 100 kg/m³), clamped at
/// x = 0 and sagging under gravity, warped stiffness with light Rayleigh damping, dt = 10 ms, CG to
/// a relative residual of 1e-5. Its node group `tip` (the free end face) takes wrenches.
/// config/scenes/cantilever.yaml is the same scene as a file.
SceneSpec defaultScene();

}  // namespace deformable_sim::core
