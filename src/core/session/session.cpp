#include "deformable_sim/core/session/session.h"

#include <cmath>
#include <type_traits>

#include "deformable_sim/core/elements/parameter_limits.h"

namespace deformable_sim::core {

Session::Session(SceneSpec spec, std::vector<Mesh> meshes, CommandLimits limits,
                 std::vector<std::optional<EmbeddedSurface>> surfaces)
    : spec_(std::move(spec)),
      meshes_(std::move(meshes)),
      limits_(limits),
      surfaces_(std::move(surfaces)) {
  rebuild();
}

void Session::rebuild() {
  commands_.reset();  // it refers to the simulation it replaces
  simulation_ = std::make_unique<Simulation>(spec_, meshes_);
  for (size_t b = 0; b < surfaces_.size(); ++b) {
    if (surfaces_[b]) simulation_->setEmbeddedSurface(static_cast<int>(b), *surfaces_[b]);
  }
  simulation_->refuseBodiesInsideEachOther();
  commands_ = std::make_unique<CommandProcessor>(*simulation_, limits_);
}

int Session::apply(const SessionCommand& command) {
  const long step = simulation_->stepCount();
  const int nodes = std::visit(
      [this](const auto& c) -> int {
        using T = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<T, ClearWrenchCommand>) {
          return commands_->clearWrench(c.source) ? 1 : 0;
        } else if constexpr (std::is_same_v<T, ReleaseGraspCommand>) {
          const auto found = commands_->grasps().find(c.name);
          if (found == commands_->grasps().end()) {
            throw CommandError("no grasp named '" + c.name + "'");
          }
          const int released = static_cast<int>(found->second.nodes.size());
          commands_->releaseGrasp(c.name);
          return released;
        } else if constexpr (std::is_same_v<T, MoveGraspCommand>) {
          if (commands_->grasps().count(c.name) == 0) {
            throw CommandError("no grasp named '" + c.name + "'");
          }
          if (!c.frame.matrix().allFinite()) {
            throw CommandError("grasp '" + c.name + "': the frame's pose is not finite");
          }
          commands_->moveGrasp(c.name, c.frame);
          return static_cast<int>(commands_->grasps().at(c.name).nodes.size());
        } else if constexpr (std::is_same_v<T, SetObstaclesCommand>) {
          for (size_t k = 0; k < c.obstacles.size(); ++k) {
            try {
              validate(c.obstacles[k].shape, "obstacle '" + c.obstacles[k].name + "'");
            } catch (const std::invalid_argument& e) {
              throw CommandError(e.what());
            }
            if (!c.obstacles[k].pose.matrix().allFinite()) {
              throw CommandError("obstacle '" + c.obstacles[k].name + "': pose is not finite");
            }
          }
          simulation_->obstacles() = c.obstacles;
          return 0;
        } else if constexpr (std::is_same_v<T, TuneCommand>) {
          return applyTune(c);
        } else if constexpr (std::is_same_v<T, ResetCommand>) {
          rebuild();
          ++episode_;
          return 0;
        } else {
          return commands_->apply(c);
        }
      },
      command);
  if (listener_) {
    const bool reset = std::holds_alternative<ResetCommand>(command);
    listener_(AppliedCommand{episode_, reset ? 0 : step, command});
  }
  return nodes;
}

int Session::applyTune(const TuneCommand& command) {
  std::vector<Body*> bodies;
  for (Body& body : simulation_->bodies()) {
    if (command.body.empty() || body.name() == command.body) bodies.push_back(&body);
  }
  if (bodies.empty()) throw CommandError("tune: no body named '" + command.body + "'");
  // Check everything first, so that a refused command changes nothing.
  try {
    if (command.material) validate(*command.material);
    if (command.damping) checkDamping(command.damping->mass, command.damping->stiffness);
    checkSolverLimits(command.solver_tolerance.value_or(1.0),
                      command.solver_max_iterations.value_or(1));
  } catch (const std::invalid_argument& e) {
    throw CommandError(std::string("tune: ") + e.what());
  }
  if (command.dt && !(*command.dt > 0.0 && std::isfinite(*command.dt))) {
    throw CommandError("tune: dt must be finite and > 0 s");
  }
  BodyTuning tuning;
  tuning.material = command.material;
  tuning.damping = command.damping;
  tuning.solver_tolerance = command.solver_tolerance;
  tuning.solver_max_iterations = command.solver_max_iterations;
  for (Body* body : bodies) body->tune(tuning);
  if (command.dt) simulation_->setDt(*command.dt);
  return 0;
}

}  // namespace deformable_sim::core
