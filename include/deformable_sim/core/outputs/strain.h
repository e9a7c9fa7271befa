// A scalar strain per node, for colouring the surface: how far each element is from its rest shape
// once its rotation is taken out.
#pragma once

#include <vector>

#include "deformable_sim/core/bodies/body.h"

namespace deformable_sim::core {

/// For each node, the largest over its elements of ‖sym(Rᵀ F) − I‖ (Frobenius; R the polar
/// rotation of F): the corotated small strain, dimensionless, 0 at rest and for rigid motions.
/// `strain` is resized to the number of nodes.
void nodalStrain(const Body& body, std::vector<double>& strain);

}  // namespace deformable_sim::core
