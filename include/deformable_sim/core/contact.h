// Contact with rigid obstacles (the `contact` effect): after each step, nodes that ended up inside
// an obstacle are put back on its surface, their velocity into it removed and, with friction,
// their sliding slowed (Coulomb's law at the velocity level). A projection, so it is stable at any
// stiffness and step, and costs nothing when the scene does not enable it.
#pragma once

#include <vector>

#include "deformable_sim/core/fem_body.h"
#include "deformable_sim/core/shape.h"

namespace deformable_sim::core {

struct ContactSettings {
  double friction = 0.0;  ///< Coulomb coefficient μ >= 0 (0: frictionless)
};

/// Projects the free nodes of `body` out of every obstacle. Returns the number of nodes that were
/// in contact. Allocates nothing.
int resolveContacts(FemBody& body, const std::vector<PlacedShape>& obstacles,
                    const ContactSettings& settings);

}  // namespace deformable_sim::core
