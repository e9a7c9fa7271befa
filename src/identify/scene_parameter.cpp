#include "deformable_sim/identify/scene_parameter.h"

#include <sstream>

namespace deformable_sim::identify {

namespace {

core::BodySpec& bodyOf(core::SceneSpec& scene, const FitParameter& p) {
  for (core::BodySpec& body : scene.bodies) {
    if (body.name == p.body) return body;
  }
  std::string names;
  for (const core::BodySpec& body : scene.bodies) names += (names.empty() ? "" : ", ") + body.name;
  throw FitSpecError(p.key + ".body: the scene has no body '" + p.body + "' (it has " + names +
                     ")");
}

// The damping the body simulates: its own effects' or, when it has none, the scene's.
core::RayleighDamping& dampingOf(core::SceneSpec& scene, core::BodySpec& body,
                                 const FitParameter& p) {
  core::BodyEffects& effects = body.effects ? *body.effects : scene.effects;
  if (!effects.damping) {
    throw FitSpecError(p.key + ".parameter: body '" + p.body +
                       "' has no damping: add effects: {damping: {mass: 0, stiffness: 0}} to "
                       "the scene");
  }
  return *effects.damping;
}

double& valueOf(core::SceneSpec& scene, const FitParameter& p) {
  core::BodySpec& body = bodyOf(scene, p);
  if (p.parameter == "youngs_modulus") return body.material.youngs_modulus;
  if (p.parameter == "poisson_ratio") return body.material.poisson_ratio;
  if (p.parameter == "density") return body.material.density;
  if (p.parameter == "damping_mass") return dampingOf(scene, body, p).mass;
  if (p.parameter == "damping_stiffness") return dampingOf(scene, body, p).stiffness;
  if (!scene.contact) {
    throw FitSpecError(p.key + ".parameter: friction needs the scene's contact effect");
  }
  return scene.contact->friction;
}

}  // namespace

double parameterValue(const core::SceneSpec& scene, const FitParameter& parameter) {
  core::SceneSpec copy = scene;
  return valueOf(copy, parameter);
}

void setParameter(core::SceneSpec& scene, const FitParameter& parameter, double value) {
  if (parameter.observation >= 0) return;  // a time offset: the measurements', not the scene's
  core::BodySpec& body = bodyOf(scene, parameter);
  const bool damping = parameter.parameter.rfind("damping_", 0) == 0;
  // Several bodies may share the scene's damping: the fitted body gets its own copy.
  if (damping && !body.effects && scene.bodies.size() > 1) body.effects = scene.effects;
  valueOf(scene, parameter) = value;
}

std::vector<double> firstGuess(const core::SceneSpec& scene,
                               const std::vector<FitParameter>& parameters) {
  std::vector<double> guess;
  for (const FitParameter& p : parameters) {
    if (p.observation >= 0) {  // a time offset starts from none (readFitSpec checked 0 is in)
      guess.push_back(0.0);
      continue;
    }
    const double value = parameterValue(scene, p);
    if (!(value >= p.min && value <= p.max)) {
      std::ostringstream text;
      text << p.key << ": the scene's " << p.parameter << " of '" << p.body << "', " << value
           << ", the first guess, is outside [min, max] = [" << p.min << ", " << p.max << "]";
      throw FitSpecError(text.str());
    }
    guess.push_back(value);
  }
  return guess;
}

}  // namespace deformable_sim::identify
