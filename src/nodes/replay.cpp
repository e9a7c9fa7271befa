// deformable_sim_replay: re-simulates a recorded session offline and reports how far the
// re-simulation is from what was recorded (same build, same settings: exactly zero).
#include "deformable_sim/ros/replay.h"

#include <ros/time.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <string>
#include <thread>

#include "sleeping_openmp_threads.h"

namespace {

namespace rl = deformable_sim::ros_layer;

constexpr const char* kUsage =
    "usage: deformable_sim_replay IN.bag [--out OUT.bag] [--node NAME] [--solver cg|direct]\n"
    "                             [--tolerance TOL] [--max-iterations N] [--threads N]\n"
    "                             [--quiet] [--help]\n"
    "  Re-runs the session recorded in IN.bag (the node's ~scene, ~applied and ~state) and "
    "reports\n"
    "  the largest difference from the recorded states.\n"
    "  --out OUT.bag       write the re-simulated ~state, ~mesh and /tf to OUT.bag\n"
    "  --node NAME         the node whose session to replay (when IN.bag holds several)\n"
    "  --solver, --tolerance, --max-iterations\n"
    "                      re-simulate with other solver settings: what would have happened\n"
    "  --threads N         threads for the simulation (default: the machine's cores); the\n"
    "                      results are the same bits on any count\n"
    "  --quiet             no progress bar\n"
    "  -h, --help          this text\n";

struct Arguments {
  rl::ReplayOptions options;
  bool quiet = false;
  bool help = false;
};

// A number that fills the whole text and lies in [low, high].
bool number(const char* text, double low, double high, double& value) {
  char* end = nullptr;
  value = std::strtod(text, &end);
  return end != text && *end == '\0' && value >= low && value <= high;
}

// Reads the option at argv[i] (and its value, moving i past it); false if it is not one.
bool parseOption(int argc, char** argv, int& i, Arguments& arguments) {
  rl::ReplayOptions& options = arguments.options;
  const std::string arg = argv[i];
  const char* next = i + 1 < argc ? argv[i + 1] : nullptr;
  double value = 0.0;
  if (arg == "-h" || arg == "--help") {
    arguments.help = true;
    return true;
  }
  if (arg == "--quiet") {
    arguments.quiet = true;
    return true;
  }
  if (!next) return false;
  if (arg == "--out") {
    options.output = next;
  } else if (arg == "--node") {
    options.node = next;
    if (!options.node.empty() && options.node[0] != '/') options.node = "/" + options.node;
  } else if (arg == "--solver") {
    options.solver_method = std::string(next);
  } else if (arg == "--tolerance" && number(next, 0.0, std::numeric_limits<double>::max(), value) &&
             value > 0.0) {
    options.solver_tolerance = value;
  } else if (arg == "--max-iterations" && number(next, 1.0, 1e9, value)) {
    options.solver_max_iterations = static_cast<int>(value);
  } else if (arg == "--threads" && number(next, 1.0, 64.0, value)) {
    options.threads = static_cast<int>(value);
  } else {
    return false;
  }
  ++i;
  return true;
}

// False, naming the bad argument on stderr, unless every argument is understood.
bool parseArguments(int argc, char** argv, Arguments& arguments) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (!arg.empty() && arg[0] != '-' && arguments.options.input.empty()) {
      arguments.options.input = arg;
    } else if (!parseOption(argc, argv, i, arguments)) {
      std::cerr << "deformable_sim_replay: bad argument '" << arg << "'\n";
      return false;
    }
  }
  return true;
}

void printReport(const rl::ReplayReport& replay, const rl::ReplayOptions& options) {
  const deformable_sim::core::ResimulationReport& report = replay.resimulation;
  std::printf(
      "node %s: re-simulated %ld steps (%.2f s simulated) in %.3f s on %d thread%s: %.1fx real "
      "time, %.1f CG iterations a step\n",
      replay.node.c_str(), report.steps, report.simulated_time, replay.wall_time, replay.threads,
      replay.threads == 1 ? "" : "s",
      replay.wall_time > 0.0 ? report.simulated_time / replay.wall_time : 0.0,
      report.steps > 0 ? static_cast<double>(report.solver_iterations) / report.steps : 0.0);
  const bool exact = report.compared_states > 0 && report.max_position_difference == 0.0 &&
                     report.max_velocity_difference == 0.0;
  std::printf(
      "compared %ld recorded states: largest difference %.17g m in position, %.17g m/s "
      "in velocity%s\n",
      report.compared_states, report.max_position_difference, report.max_velocity_difference,
      exact ? " (bit-exact)" : "");
  if (report.first_difference_step >= 0) {
    std::printf("the states first differ at step %ld of episode %ld\n",
                report.first_difference_step, report.first_difference_episode);
  }
  const bool same_settings =
      !options.solver_method && !options.solver_tolerance && !options.solver_max_iterations;
  if (report.refused_commands > 0) {
    std::printf("%ld recorded commands were refused by the re-simulation%s\n",
                report.refused_commands,
                same_settings ? "" : " (it went another way with these settings)");
  }
  if (!options.output.empty()) std::printf("wrote %s\n", options.output.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  deformable_sim::letOpenMpThreadsSleep(argv);
  Arguments arguments;
  if (!parseArguments(argc, argv, arguments)) {
    std::cerr << kUsage;
    return 2;
  }
  if (arguments.help) {
    std::cout << kUsage;
    return 0;
  }
  rl::ReplayOptions& options = arguments.options;
  if (options.input.empty()) {
    std::cerr << kUsage;
    return 2;
  }
  // The results are the same bits on any thread count, so an offline re-simulation takes every
  // core the machine has, whatever the recording node ran on.
  if (!options.threads) {
    options.threads = static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 64u));
  }
  ros::Time::init();
  try {
    rl::Replay replay(options);
    printReport(replay.run(arguments.quiet ? nullptr : stderr), options);
  } catch (const rl::ReplayError& e) {
    std::cerr << "deformable_sim_replay: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
