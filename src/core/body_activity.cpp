#include "deformable_sim/core/body_activity.h"

namespace deformable_sim::core {

std::vector<std::string> activeEffects(const Simulation& simulation, int body) {
  const Body& b = simulation.bodies()[body];
  std::vector<std::string> names = effectNames(b.effects(), b.model());
  if (simulation.contact() && b.model() == BodyModel::kFiniteElement) names.emplace_back("contact");
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

}  // namespace deformable_sim::core
