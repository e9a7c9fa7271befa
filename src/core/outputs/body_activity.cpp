#include "deformable_sim/core/outputs/body_activity.h"

namespace deformable_sim::core {

std::vector<std::string> activeEffects(const Simulation& simulation, int body) {
  const Body& b = simulation.bodies()[body];
  std::vector<std::string> names = effectNames(b.settings().effects, b.settings().model);
  if (simulation.contact() && b.finiteElements()) names.emplace_back("contact");
  return names;
}

int graspedNodes(const CommandProcessor& commands, int body) {
  int nodes = 0;
  for (const auto& [name, grasp] : commands.grasps()) {
    if (grasp.body == body) nodes += static_cast<int>(grasp.nodes.size());
  }
  return nodes;
}

int appliedWrenches(const CommandProcessor& commands, int body) {
  int wrenches = 0;
  for (const auto& [source, wrench] : commands.activeWrenches()) wrenches += wrench.body == body;
  return wrenches;
}

std::string bodySummary(const Simulation& simulation, int body) {
  const Body& b = simulation.bodies()[body];
  std::string effects;
  for (const std::string& name : activeEffects(simulation, body)) {
    effects += (effects.empty() ? "" : ", ") + name;
  }
  return "body '" + b.name() + "' (" + modelName(b.settings().model) +
         "): " + std::to_string(b.numNodes()) + " nodes, " +
         std::to_string(b.mesh().numTetrahedra()) + " tetrahedra, " +
         std::to_string(b.mesh().cells.size()) + " other elements, " +
         std::to_string(numConstrained(b)) +
         " fixed; effects: " + (effects.empty() ? "none" : effects);
}

}  // namespace deformable_sim::core
