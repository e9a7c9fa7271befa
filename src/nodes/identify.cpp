// deformable_sim_identify: fits a body's material (E, nu, density, damping, friction) to a
// recorded session, against the tracked frames and force/torque sensors measured in it.
#include <ros/time.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <thread>

#include "deformable_sim/identify/fit_spec.h"
#include "deformable_sim/ros/identification.h"
#include "deformable_sim/ros/replay.h"
#include "sleeping_openmp_threads.h"

namespace {

namespace rl = deformable_sim::ros_layer;

constexpr const char* kUsage =
    "usage: deformable_sim_identify FIT.yaml [--threads N] [--plot FILE.png [--residuals]]\n"
    "                               [--max-iterations N] [--help]\n"
    "  Fits scene parameters to a recorded session: the bag's ~applied log is re-simulated with\n"
    "  trial values (bounded least squares, Ceres Solver) against the tracked frames (/tf) and\n"
    "  force/torque sensors (WrenchStamped) measured in the same session. FIT.yaml:\n"
    "    bag: experiment.bag     # ~applied as the node recorded it, plus the measurements\n"
    "    scene: scene.yaml       # optional: the scene to start from (else the bag's ~scene)\n"
    "    fit:                    # youngs_modulus, poisson_ratio, density, damping_mass,\n"
    "      - {body: beam, parameter: youngs_modulus, min: 1.0e4, max: 1.0e7}  # "
    "damping_stiffness,\n"
    "    observations:           # friction\n"
    "      - {tf: marker_tip, body: beam, at: [0.3, 0.03, 0.02], sigma: 0.001}\n"
    "      - {wrench: /ft_sensor/wrench, reactions: beam, sigma: [0.02, 0.002]}  # or grasp: "
    "NAME,\n"
    "    out: fitted.yaml        # the scene with the fitted values          # link: NAME\n"
    "  Paths are relative to FIT.yaml. Prints a line per iteration, 'fitted BODY PARAMETER VALUE\n"
    "  ± STD' per parameter (1 sigma, scaled by the weighted RMS residual where it exceeds 1),\n"
    "  their correlations and the RMS residual of each observation before and after.\n"
    "  --threads N        re-simulations at once (default: the machine's cores)\n"
    "  --plot FILE.png    draw measured against simulated (first guess, fit) over time\n"
    "  --residuals        with --plot: draw simulated minus measured instead\n"
    "  --max-iterations N of the solver (default 30): a fit that needs more did not converge\n"
    "  -h, --help         this text\n"
    "  Exit status: 0 fitted, 1 input refused, 2 bad arguments, 3 the fit did not converge,\n"
    "  4 fitted but not to be trusted (a parameter at a bound or with no effect on the data,\n"
    "  or a weighted RMS residual above 3).\n";

// scripts/plot_identify.py: installed beside the program; in a build, in the source tree.
std::string plotScript() {
  std::error_code error;
  const std::filesystem::path beside =
      std::filesystem::read_symlink("/proc/self/exe", error).parent_path() / "plot_identify.py";
  return !error && std::filesystem::exists(beside) ? beside.string() : DEFORMABLE_SIM_PLOT_SCRIPT;
}

bool parseArguments(int argc, char** argv, rl::IdentifyOptions& options, bool& help) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const char* next = i + 1 < argc ? argv[i + 1] : nullptr;
    if (arg == "-h" || arg == "--help") {
      help = true;
    } else if ((arg == "--threads" || arg == "--max-iterations") && next) {
      char* end = nullptr;
      const long n = std::strtol(next, &end, 10);
      if (end == next || *end != '\0' || n < 1 || n > (arg == "--threads" ? 64 : 10000)) {
        std::cerr << "deformable_sim_identify: bad value of " << arg << ": '" << next << "'\n";
        return false;
      }
      (arg == "--threads" ? options.threads : options.max_iterations) = static_cast<int>(n);
      ++i;
    } else if (arg == "--residuals") {
      options.plot_residuals = true;
    } else if (arg == "--plot" && next) {
      options.plot = next;
      ++i;
    } else if (!arg.empty() && arg[0] != '-' && options.fit_file.empty()) {
      options.fit_file = arg;
    } else {
      std::cerr << "deformable_sim_identify: bad argument '" << arg << "'\n";
      return false;
    }
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  deformable_sim::letOpenMpThreadsSleep(argv);
  rl::IdentifyOptions options;
  options.threads = static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 64u));
  options.plot_script = plotScript();
  bool help = false;
  if (!parseArguments(argc, argv, options, help)) {
    std::cerr << kUsage;
    return 2;
  }
  if (help) {
    std::cout << kUsage;
    return 0;
  }
  if (options.fit_file.empty()) {
    std::cerr << kUsage;
    return 2;
  }
  ros::Time::init();
  try {
    return rl::identify(options, stdout).exit_code;
  } catch (const std::exception& e) {
    std::cerr << "deformable_sim_identify: " << e.what() << "\n";
    return 1;
  }
}
