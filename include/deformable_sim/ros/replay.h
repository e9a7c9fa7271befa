// Re-simulation of a recorded session: the scene (~scene) and the log of applied commands
// (~applied) are read from a bag, run again offline as fast as the machine allows, written to a
// new bag (state, mesh, tf), and compared with the states recorded (~state).
#pragma once

#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>

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
  long steps = 0;                        ///< steps re-simulated, all episodes
  double simulated_time = 0.0;           ///< s
  double wall_time = 0.0;                ///< s
  int threads = 1;                       ///< threads the simulation ran on
  long solver_iterations = 0;            ///< CG iterations, all steps and bodies
  long compared_states = 0;              ///< recorded body states compared with the re-simulation
  double max_position_difference = 0.0;  ///< m, largest over nodes and states
  double max_velocity_difference = 0.0;  ///< m/s
  long refused_commands = 0;             ///< recorded commands the re-simulation refused
  long first_difference_episode = -1;    ///< where the states first differ (-1: nowhere)
  long first_difference_step = -1;
};

/// Throws ReplayError naming the problem: a bag that cannot be read (truncated, not a bag), one
/// without a recorded scene, several nodes and none chosen, a log that does not start at a step 0.
/// Writes a progress bar to `progress` (nullptr: none).
ReplayReport replay(const ReplayOptions& options, std::ostream* progress);

}  // namespace deformable_sim::ros_layer
