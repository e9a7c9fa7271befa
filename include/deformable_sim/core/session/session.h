// A running simulation and everything that may change it, as one log of commands: a session
// applies each command between steps and tells a listener which command took effect at which
// step. Replaying the same log on a session built from the same scene and meshes gives the same
// states bit for bit (same build): the node records the log on ~applied, deformable_sim_replay
// re-runs it.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "deformable_sim/core/elements/mesh.h"
#include "deformable_sim/core/session/commands.h"
#include "deformable_sim/core/session/scene.h"
#include "deformable_sim/core/session/simulation.h"

namespace deformable_sim::core {

/// Removes the wrench a source applied.
struct ClearWrenchCommand {
  std::string source;
};
/// Returns a grasp's nodes to free motion.
struct ReleaseGraspCommand {
  std::string name;
};
/// Moves a grasp's frame: its nodes reach their place in it at the end of the next step.
struct MoveGraspCommand {
  std::string name;
  Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();  ///< world
};
/// Replaces the obstacles of the contact effect (their world poses, e.g. from tf).
struct SetObstaclesCommand {
  std::vector<PlacedShape> obstacles;
};
/// Live tuning: what is set changes, between steps, for the body named (empty: every body).
struct TuneCommand {
  std::string body;
  std::optional<LinearElasticMaterial> material;
  std::optional<RayleighDamping> damping;
  std::optional<double> solver_tolerance;
  std::optional<int> solver_max_iterations;
  std::optional<double> dt;  ///< s, every body
};
/// Back to the scene's initial state: a new episode starts at step 0.
struct ResetCommand {};

using SessionCommand =
    std::variant<WrenchCommand, ClearWrenchCommand, FixCommand, GraspCommand, ReleaseGraspCommand,
                 MoveGraspCommand, SetObstaclesCommand, TuneCommand, ResetCommand>;

/// A command as it took effect: after `step` steps of episode `episode` (resets so far).
struct AppliedCommand {
  long episode = 0;
  long step = 0;
  SessionCommand command;
};

class Session {
 public:
  /// meshes[i] belongs to spec.bodies[i]; both are kept for resets. Throws std::invalid_argument
  /// like Simulation.
  /// surfaces[i], when given, is the surface body i was made from (Simulation::embeddedSurface).
  Session(SceneSpec spec, std::vector<Mesh> meshes, CommandLimits limits = {},
          std::vector<std::optional<EmbeddedSurface>> surfaces = {});

  /// Applies a command; throws CommandError (naming the problem) and changes nothing when it is
  /// refused. On success the listener hears of it; returns the number of nodes acted on.
  int apply(const SessionCommand& command);
  /// One step of every body.
  void step(std::vector<StepReport>& reports) { simulation_->step(reports); }

  /// Called with every command that took effect, after it did.
  void setListener(std::function<void(const AppliedCommand&)> listener) {
    listener_ = std::move(listener);
  }

  long episode() const { return episode_; }
  Simulation& simulation() { return *simulation_; }
  const Simulation& simulation() const { return *simulation_; }
  const CommandProcessor& commands() const { return *commands_; }
  CommandProcessor& commands() { return *commands_; }
  const SceneSpec& scene() const { return spec_; }
  const std::vector<Mesh>& meshes() const { return meshes_; }
  const std::vector<std::optional<EmbeddedSurface>>& surfaces() const { return surfaces_; }

 private:
  int applyTune(const TuneCommand& command);
  void rebuild();

  SceneSpec spec_;
  std::vector<Mesh> meshes_;
  CommandLimits limits_;
  std::vector<std::optional<EmbeddedSurface>> surfaces_;
  std::unique_ptr<Simulation> simulation_;
  std::unique_ptr<CommandProcessor> commands_;
  long episode_ = 0;
  std::function<void(const AppliedCommand&)> listener_;
};

}  // namespace deformable_sim::core
