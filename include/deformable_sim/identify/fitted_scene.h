// The scene file with fitted values in place of the scene's own: `out` of a fit.
#pragma once

#include <string>
#include <vector>

#include "deformable_sim/identify/fit_spec.h"

namespace deformable_sim::identify {

/// `scene_yaml` (a scene file's text) with each parameter set to its value: a body's material,
/// its damping (its own effects', else the scene's), or the contact effect's friction. Comments
/// are not kept. Throws FitSpecError naming the parameter's key when the text has no such body.
std::string fittedSceneYaml(const std::string& scene_yaml,
                            const std::vector<FitParameter>& parameters,
                            const std::vector<double>& values);

}  // namespace deformable_sim::identify
