// What is going on with one body of a running session, for its line in the node's statistics
// and log: what it is made of, the effects it runs, the nodes grasps hold, the wrenches that
// push it.
#pragma once

#include <string>
#include <vector>

#include "deformable_sim/core/session/commands.h"

namespace deformable_sim::core {

/// The body's effects by name (effectNames), with "contact" where the scene's contact acts on it.
std::vector<std::string> activeEffects(const Simulation& simulation, int body);
/// Nodes of the body held by grasps.
int graspedNodes(const CommandProcessor& commands, int body);
/// Wrenches in effect on the body.
int appliedWrenches(const CommandProcessor& commands, int body);
/// One line on the body for a log: "body 'beam' (fem): 425 nodes, 1536 tetrahedra, 0 other
/// elements, 25 fixed; effects: gravity, warping" ("effects: none" when it runs none).
std::string bodySummary(const Simulation& simulation, int body);

}  // namespace deformable_sim::core
