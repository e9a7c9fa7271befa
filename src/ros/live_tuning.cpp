#include "deformable_sim/ros/live_tuning.h"

namespace deformable_sim::ros_layer {

namespace {

core::LiveSettings fromConfig(const SimConfig& c) {
  return {c.body,         c.youngs_modulus,    c.poisson_ratio,    c.density,
          c.damping_mass, c.damping_stiffness, c.solver_tolerance, c.solver_max_iterations,
          c.rate};
}

SimConfig toConfig(const core::LiveSettings& s) {
  SimConfig c;
  c.body = s.body;
  c.youngs_modulus = s.youngs_modulus;
  c.poisson_ratio = s.poisson_ratio;
  c.density = s.density;
  c.damping_mass = s.damping_mass;
  c.damping_stiffness = s.damping_stiffness;
  c.solver_tolerance = s.solver_tolerance;
  c.solver_max_iterations = s.solver_max_iterations;
  c.rate = s.rate;
  return c;
}

}  // namespace

LiveTuning::LiveTuning(const ros::NodeHandle& private_node, const core::Session& session,
                       double rate, int substeps, Apply apply, Refuse refuse,
                       std::function<void(double)> on_rate)
    : session_(session),
      substeps_(substeps),
      apply_(std::move(apply)),
      refuse_(std::move(refuse)),
      on_rate_(std::move(on_rate)),
      applied_(core::liveSettings(session.simulation().bodies().front(), rate)),
      scene_(applied_),
      server_(std::make_unique<dynamic_reconfigure::Server<SimConfig>>(mutex_, private_node)) {
  // Start from the scene's values so that the first callback changes nothing.
  SimConfig initial = toConfig(applied_);
  server_->updateConfig(initial);
  server_->setCallback([this](SimConfig& config, uint32_t) { onReconfigure(config); });
}

void LiveTuning::reapply() {
  SimConfig tuned = toConfig(applied_);
  const std::string body = applied_.body;
  applied_ = scene_;
  applied_.body = body;
  onReconfigure(tuned);
}

void LiveTuning::onReconfigure(SimConfig& config) {
  const core::LiveSettings after = fromConfig(config);
  try {
    for (const core::TuneCommand& tune :
         core::tuneCommands(session_.simulation(), applied_, after, substeps_)) {
      apply_(tune);
    }
  } catch (const core::CommandError& e) {
    refuse_(std::string(e.what()) + "; the parameters keep their values");
    config = toConfig(applied_);  // the server answers with what is in effect
    return;
  }
  if (after.rate != applied_.rate) on_rate_(after.rate);
  applied_ = after;
}

}  // namespace deformable_sim::ros_layer
