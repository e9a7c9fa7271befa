// What touched what in the last step, for the node's ~contacts and the robot links' contact
// wrenches: one entry per touching pair (a body and an obstacle, two bodies, a body and itself).
#pragma once

#include <string>
#include <vector>

#include "deformable_sim/core/contact/contact.h"
#include "deformable_sim/core/session/simulation.h"

namespace deformable_sim::core {

struct ContactPair {
  enum class Kind { kObstacle, kBody, kSelf };
  int body = 0;  ///< index in Simulation::bodies()
  Kind kind = Kind::kObstacle;
  /// kObstacle: the obstacles' name (a URDF link's shapes are one pair); kBody: the other body's
  /// name; kSelf: the body's own.
  std::string other;
  ContactLoad load;  ///< on `body`, from `other`
};

/// The pairs that touched in the last step: body by body, its obstacles in their order (shapes
/// of one name merged), then the bodies it touched. Reuses `pairs`' storage.
void touchingPairs(const Simulation& sim, std::vector<ContactPair>& pairs);

/// The force and the torque about the world origin that the bodies exerted on the obstacles
/// named `name` (a robot link) in the last step: the opposite of what they felt from it.
ContactLoad loadOnObstacle(const std::vector<ContactPair>& pairs, const std::string& name);

}  // namespace deformable_sim::core
