// Re-simulation of a recorded session: the scene, its meshes and the log of commands as they took
// effect are run again on a new Session, step by step, and every re-simulated state is compared
// with the state recorded at the same step. The same build with the same settings gives exactly
// zero difference (a session repeats its log bit for bit); other solver settings show what would
// have happened. The ROS layer reads the log from a bag and writes what it is shown to another.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "deformable_sim/core/base/progress_bar.h"
#include "deformable_sim/core/elements/mesh.h"
#include "deformable_sim/core/session/scene.h"
#include "deformable_sim/core/session/session.h"

namespace deformable_sim::core {

/// A log that cannot be re-simulated (it starts mid-episode without a reset, it is out of
/// order, a state does not fit its body); the message names the problem.
class ResimulationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A body's state as it was recorded.
struct RecordedState {
  Eigen::VectorXd positions;   ///< m, x y z of every node, world
  Eigen::VectorXd velocities;  ///< m/s, likewise
  /// The caller's number for where the state came from (e.g. the index of its message), handed
  /// back with the comparison.
  std::size_t source = 0;
};

/// episode (resets since the recording session started), step of the episode, body name.
using RecordedStateKey = std::tuple<long, long, std::string>;

struct Recording {
  /// The commands in the order they took effect, as a Session's listener reports them.
  std::vector<AppliedCommand> log;
  std::map<RecordedStateKey, RecordedState> states;
};

/// Other solver limits than the recorded ones; kept through resets and tuning commands.
struct SolverOverride {
  std::optional<double> tolerance;
  std::optional<int> max_iterations;
};

struct ResimulationReport {
  long steps = 0;                        ///< steps re-simulated, all episodes
  double simulated_time = 0.0;           ///< s
  long solver_iterations = 0;            ///< CG iterations, all steps and bodies
  long compared_states = 0;              ///< recorded body states compared
  double max_position_difference = 0.0;  ///< m, largest over nodes and states
  double max_velocity_difference = 0.0;  ///< m/s
  long refused_commands = 0;             ///< recorded commands the re-simulation refused
  long first_difference_episode = -1;    ///< where the states first differ (-1: nowhere)
  long first_difference_step = -1;
};

/// A recorded state and the re-simulated body at the same step.
struct ComparedState {
  long episode = 0;  ///< as recorded
  long step = 0;
  int body = 0;  ///< index in simulation.bodies()
  const Simulation& simulation;
  const RecordedState& recorded;
  double position_difference = 0.0;  ///< m, largest over the nodes
  double velocity_difference = 0.0;  ///< m/s
};

class Resimulation {
 public:
  using Observer = std::function<void(const ComparedState&)>;
  /// Hears of the session at the start and after every step, recorded state or not.
  using StepObserver = std::function<void(const Session&)>;

  /// meshes[i] belongs to spec.bodies[i]. The log starts where the recording does: at the
  /// session's start (its first state is step 0 of episode 0) or at its first reset; commands
  /// before that reset are skipped. Throws ResimulationError when the recording starts later and
  /// holds no reset, std::invalid_argument for a scene that cannot be built (like Session).
  /// `surfaces`: those bodies were made from, as for Session.
  Resimulation(SceneSpec spec, std::vector<Mesh> meshes, Recording recording,
               SolverOverride solver = {},
               std::vector<std::optional<EmbeddedSurface>> surfaces = {});

  /// Steps the run will take (each episode up to its last command or recorded state).
  long plannedSteps() const { return planned_steps_; }
  /// The session re-simulated (its simulation is replaced at every reset).
  const Session& session() const { return session_; }
  /// Runs `episode` at least to `step`: what was measured after the last command.
  void extendTo(long episode, long step);
  void setStepObserver(StepObserver observer) { step_observer_ = std::move(observer); }

  /// Runs the whole log (once: a second call throws std::logic_error); `observer` hears of every
  /// compared state, `progress` (may be null) of every step. Throws ResimulationError for a log out
  /// of order or a recorded state with another number of nodes than its body.
  ResimulationReport run(const Observer& observer = {}, ProgressBar* progress = nullptr);

 private:
  std::pair<long, long> recordingStart() const;
  void findStart();
  void indexStates();
  void planSteps();
  long recordedEpisode() const { return session_.episode() + episode_offset_; }
  long endStep(long episode) const;
  void checkOrder(const AppliedCommand& applied) const;
  void apply(const AppliedCommand& applied);
  void overrideSolver();
  void stepTo(long step);
  void compare();
  void compareBody(long episode, int body, const RecordedState& recorded);

  Session session_;
  Recording recording_;
  SolverOverride solver_;
  std::size_t first_command_ = 0;  ///< where the log starts
  bool from_start_ = true;         ///< at the session's start, not at a reset
  long episode_offset_ = 0;        ///< recorded episode = the session's episode + this
  /// The recorded states of each (episode, step), one slot per body (null: none recorded).
  std::map<std::pair<long, long>, std::vector<const RecordedState*>> states_by_step_;
  std::map<long, long> end_steps_;  ///< per recorded episode: the last step to re-simulate
  long planned_steps_ = 0;
  bool ran_ = false;
  std::vector<StepReport> step_reports_;
  ResimulationReport report_;
  const Observer* observer_ = nullptr;
  ProgressBar* progress_ = nullptr;
  StepObserver step_observer_;
};

}  // namespace deformable_sim::core
