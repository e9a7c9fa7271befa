#include "deformable_sim/core/bodies/body_effects.h"

namespace deformable_sim::core {

BodyEffects effectsOf(BodyModel model, const BodyEffects& scene,
                      const std::optional<BodyEffects>& own, bool contact) {
  BodyEffects effects = own.value_or(scene);
  if (model != BodyModel::kFiniteElement) {
    if (!own) effects.plasticity.reset();
  } else if (contact) {
    effects.reactions = true;
  }
  return effects;
}

std::vector<std::string> effectNames(const BodyEffects& effects, BodyModel model) {
  std::vector<std::string> names;
  if (effects.warping && model != BodyModel::kRigid) names.emplace_back("warping");
  if (effects.gravity) names.emplace_back("gravity");
  if (effects.damping) names.emplace_back("damping");
  if (effects.plasticity) names.emplace_back("plasticity");
  if (effects.stress_colouring) names.emplace_back("stress_colouring");
  if (effects.reactions) names.emplace_back("reactions");
  return names;
}

}  // namespace deformable_sim::core
