#include "deformable_sim/core/session/live_settings.h"

#include <sstream>

namespace deformable_sim::core {

LiveSettings liveSettings(const Body& body, double rate) {
  LiveSettings settings;
  settings.youngs_modulus = body.settings().material.youngs_modulus;
  settings.poisson_ratio = body.settings().material.poisson_ratio;
  settings.density = body.settings().material.density;
  const RayleighDamping damping = body.settings().effects.damping.value_or(RayleighDamping{});
  settings.damping_mass = damping.mass;
  settings.damping_stiffness = damping.stiffness;
  settings.solver_tolerance = body.settings().solver.tolerance;
  settings.solver_max_iterations = body.settings().solver.max_iterations;
  settings.rate = rate;
  return settings;
}

namespace {

// What changed of one body's settings; nothing set when nothing changed.
TuneCommand bodyTune(const Body& body, const LiveSettings& before, const LiveSettings& after) {
  TuneCommand tune;
  tune.body = body.name();
  if (after.youngs_modulus != before.youngs_modulus ||
      after.poisson_ratio != before.poisson_ratio || after.density != before.density) {
    LinearElasticMaterial material = body.settings().material;
    if (after.youngs_modulus != before.youngs_modulus) {
      material.youngs_modulus = after.youngs_modulus;
    }
    if (after.poisson_ratio != before.poisson_ratio) material.poisson_ratio = after.poisson_ratio;
    if (after.density != before.density) material.density = after.density;
    tune.material = material;
  }
  if (after.damping_mass != before.damping_mass ||
      after.damping_stiffness != before.damping_stiffness) {
    tune.damping = RayleighDamping{after.damping_mass, after.damping_stiffness};
  }
  if (after.solver_tolerance != before.solver_tolerance) {
    tune.solver_tolerance = after.solver_tolerance;
  }
  if (after.solver_max_iterations != before.solver_max_iterations) {
    tune.solver_max_iterations = after.solver_max_iterations;
  }
  return tune;
}

}  // namespace

std::vector<TuneCommand> tuneCommands(const Simulation& simulation, const LiveSettings& before,
                                      const LiveSettings& after, int substeps) {
  if (!after.body.empty() && simulation.bodyIndex(after.body) < 0) {
    throw CommandError("body: no body named '" + after.body + "'");
  }
  std::vector<TuneCommand> tunes;
  for (const Body& body : simulation.bodies()) {
    if (!after.body.empty() && body.name() != after.body) continue;
    TuneCommand tune = bodyTune(body, before, after);
    if (tune.material || tune.damping || tune.solver_tolerance || tune.solver_max_iterations) {
      tunes.push_back(std::move(tune));
    }
  }
  if (after.rate != before.rate) {
    if (!(after.rate >= kMinRate && after.rate <= kMaxRate)) {
      std::ostringstream message;
      message << "rate: " << after.rate << " Hz, it must be in [" << kMinRate << ", " << kMaxRate
              << "] Hz";
      throw CommandError(message.str());
    }
    TuneCommand tune;
    tune.dt = 1.0 / (after.rate * substeps);
    tunes.push_back(tune);
  }
  return tunes;
}

}  // namespace deformable_sim::core
