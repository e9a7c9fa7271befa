// Bounds beyond which a command is refused as absurd rather than applied. A wrench's default
// bound is one the body it pushes can take: ten times its weight, whatever the scene's gravity.
#pragma once

#include "deformable_sim/core/bodies/body.h"

namespace deformable_sim::core {

struct CommandLimits {
  /// N, a wrench's |force|. 0: per body, kWeightsPerWrench times its weight (mass × 9.81 m/s²).
  double max_force = 0.0;
  /// N m, a wrench's |torque|. 0: per body, its force bound times its size (the longest side of
  /// its rest bounding box).
  double max_torque = 0.0;
  double max_target_distance = 10.0;  ///< m, how far a target may be from the node now
};

/// How many times its own weight a wrench may push a body with by default. A harder push throws
/// a soft body across the scene or turns its elements inside out in a step.
constexpr double kWeightsPerWrench = 10.0;

/// The largest |force| (N) and |torque| (N m) a wrench on `body` may have.
struct WrenchBounds {
  double force = 0.0;
  double torque = 0.0;
};
WrenchBounds wrenchBounds(const Body& body, const CommandLimits& limits);

}  // namespace deformable_sim::core
