// deformable_sim_replay: re-simulates a recorded session offline and reports how far the
// re-simulation is from what was recorded (same build, same settings: exactly zero).
#include "deformable_sim/ros/replay.h"

#include <ros/time.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <thread>

namespace {

constexpr const char* kUsage =
    "usage: deformable_sim_replay IN.bag [--out OUT.bag] [--node NAME] [--solver cg|direct]\n"
    "                             [--tolerance TOL] [--max-iterations N] [--threads N]\n"
    "                             [--quiet]\n"
    "  Re-runs the session recorded in IN.bag (the node's ~scene, ~applied and ~state) and "
    "reports\n"
    "  the largest difference from the recorded states.\n"
    "  --out OUT.bag       write the re-simulated ~state, ~mesh and /tf to OUT.bag\n"
    "  --node NAME         the node whose session to replay (when IN.bag holds several)\n"
    "  --solver, --tolerance, --max-iterations\n"
    "                      re-simulate with other solver settings: what would have happened\n"
    "  --threads N         threads for the simulation (default: the machine's cores); the\n"
    "                      results are the same bits on any count\n"
    "  --quiet             no progress bar\n";

bool number(const char* text, double& value) {
  char* end = nullptr;
  value = std::strtod(text, &end);
  return end != text && *end == '\0';
}

}  // namespace

int main(int argc, char** argv) {
  deformable_sim::ros_layer::ReplayOptions options;
  bool quiet = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    double value = 0.0;
    const bool has_value = i + 1 < argc;
    if (arg == "--out" && has_value) {
      options.output = argv[++i];
    } else if (arg == "--node" && has_value) {
      options.node = argv[++i];
      if (!options.node.empty() && options.node[0] != '/') options.node = "/" + options.node;
    } else if (arg == "--solver" && has_value) {
      options.solver_method = std::string(argv[++i]);
    } else if (arg == "--tolerance" && has_value && number(argv[i + 1], value) && value > 0.0) {
      options.solver_tolerance = value;
      ++i;
    } else if (arg == "--max-iterations" && has_value && number(argv[i + 1], value) &&
               value >= 1.0) {
      options.solver_max_iterations = static_cast<int>(value);
      ++i;
    } else if (arg == "--threads" && has_value && number(argv[i + 1], value) && value >= 1.0 &&
               value <= 64.0) {
      options.threads = static_cast<int>(value);
      ++i;
    } else if (arg == "--quiet") {
      quiet = true;
    } else if (!arg.empty() && arg[0] != '-' && options.input.empty()) {
      options.input = arg;
    } else {
      std::cerr << "deformable_sim_replay: bad argument '" << arg << "'\n" << kUsage;
      return 2;
    }
  }
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
    const auto report = deformable_sim::ros_layer::replay(options, quiet ? nullptr : &std::cerr);
    const bool same_settings =
        !options.solver_method && !options.solver_tolerance && !options.solver_max_iterations;
    std::printf(
        "node %s: re-simulated %ld steps (%.2f s simulated) in %.3f s on %d thread%s: %.1fx real "
        "time, %.1f CG iterations a step\n",
        report.node.c_str(), report.steps, report.simulated_time, report.wall_time, report.threads,
        report.threads == 1 ? "" : "s",
        report.wall_time > 0.0 ? report.simulated_time / report.wall_time : 0.0,
        report.steps > 0 ? static_cast<double>(report.solver_iterations) / report.steps : 0.0);
    std::printf(
        "compared %ld recorded states: largest difference %.17g m in position, %.17g m/s "
        "in velocity%s\n",
        report.compared_states, report.max_position_difference, report.max_velocity_difference,
        report.compared_states > 0 && report.max_position_difference == 0.0 &&
                report.max_velocity_difference == 0.0
            ? " (bit-exact)"
            : "");
    if (report.first_difference_step >= 0) {
      std::printf("the states first differ at step %ld of episode %ld\n",
                  report.first_difference_step, report.first_difference_episode);
    }
    if (report.refused_commands > 0) {
      std::printf("%ld recorded commands were refused by the re-simulation%s\n",
                  report.refused_commands,
                  same_settings ? "" : " (it went another way with these settings)");
    }
    if (!options.output.empty()) std::printf("wrote %s\n", options.output.c_str());
  } catch (const deformable_sim::ros_layer::ReplayError& e) {
    std::cerr << "deformable_sim_replay: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
