// Re-simulation of a recorded session: the scene (~scene) and the log of applied commands
// (~applied) are read from a bag, run again offline as fast as the machine allows (the core's
// Resimulation), written to a new bag (state, mesh, tf), and compared with the states recorded
// (~state).
#pragma once

#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "deformable_sim/core/session/resimulation.h"

namespace deformable_sim::ros_layer {

class ReplayError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ReplayOptions {
  std::string input;   ///< the recorded bag
  std::string output;  ///< the bag to write; empty: none
  std::string node;    ///< the node's name, e.g. /deformable_sim; empty: the only one
  /// Other settings than the recorded ones: "what would have happened".
  std::optional<double> solver_tolerance;
  std::optional<int> solver_max_iterations;
  std::optional<std::string> solver_method;  ///< cg or direct
  /// Threads for the element loops and the solver. Results are the same bits on any count, so
  /// this only changes how fast; unset: the recorded scene's own setting.
  std::optional<int> threads;
  double marker_rate = 30.0;  ///< Hz of simulated time, for ~mesh in the output
};

struct ReplayReport {
  std::string node;
  int threads = 1;         ///< threads the simulation ran on
  double wall_time = 0.0;  ///< s
  core::ResimulationReport resimulation;
};

struct RecordedSession;

class Replay {
 public:
  /// Reads the bag and builds the recorded scene. Throws ReplayError naming the problem: a bag
  /// that cannot be read (truncated, not a bag), one without a recorded scene, several nodes and
  /// none chosen, a scene that cannot be built, a log that starts neither at the node's start
  /// nor at a reset.
  explicit Replay(ReplayOptions options);
  ~Replay();

  /// Re-simulates the session once, writing the output bag if asked for and a progress bar to
  /// `progress` (null: none). Throws ReplayError for a log out of order.
  ReplayReport run(std::FILE* progress);

 private:
  core::SceneSpec sceneSpec() const;
  core::ResimulationReport resimulate(std::FILE* progress);

  ReplayOptions options_;
  std::unique_ptr<RecordedSession> recorded_;
  std::unique_ptr<core::Resimulation> resimulation_;
};

}  // namespace deformable_sim::ros_layer
