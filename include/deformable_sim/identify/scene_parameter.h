// A fitted parameter in a scene: read, changed for a trial, checked against its bounds.
#pragma once

#include "deformable_sim/core/session/scene.h"
#include "deformable_sim/identify/fit_spec.h"

namespace deformable_sim::identify {

/// The value `parameter` has in `scene` (damping: the body's own effects, else the scene's).
/// Throws FitSpecError naming the key for an unknown body, and for friction or damping that the
/// scene does not simulate.
double parameterValue(const core::SceneSpec& scene, const FitParameter& parameter);

/// Sets it for its body only (friction: the scene's contact effect, all bodies).
void setParameter(core::SceneSpec& scene, const FitParameter& parameter, double value);

/// The scene's values as the first guess; throws FitSpecError naming the key when one is
/// outside its bounds.
std::vector<double> firstGuess(const core::SceneSpec& scene,
                               const std::vector<FitParameter>& parameters);

}  // namespace deformable_sim::identify
