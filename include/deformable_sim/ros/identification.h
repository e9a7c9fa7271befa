// deformable_sim_identify: fits a body's material to a recorded session. The bag's ~applied log is
// re-simulated (as deformable_sim_replay does) with trial values under a least-squares solver,
// against what was measured in the same session (tracked frames, force/torque sensors).
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "deformable_sim/identify/experiment.h"
#include "deformable_sim/identify/least_squares_fit.h"

namespace deformable_sim::ros_layer {

struct IdentifyOptions {
  std::string fit_file;
  int threads = 1;              ///< re-simulations at once
  int max_iterations = 30;      ///< of the solver: a fit that needs more has not converged
  std::string plot;             ///< PNG to draw measured against simulated; empty: none
  std::string plot_script;      ///< the script that draws it (scripts/plot_identify.py)
  bool plot_residuals = false;  ///< draw simulated minus measured instead of the values
};

struct IdentifyResult {
  identify::FitResult fit;
  std::vector<identify::ObservationRms> before, after;  ///< per observation
  /// 0; 3 when the fit did not converge; 4 when it did but cannot be trusted (a parameter at a
  /// bound or without effect on the data, or residuals far above their sigmas).
  int exit_code = 0;
};

/// Reads the fit file, the bag and the scene, fits, prints a line per iteration and the results
/// to `out`, writes the fitted scene to the fit's `out`. Throws identify::FitSpecError (a message
/// naming the file and key), ReplayError or std::runtime_error for input it cannot use.
IdentifyResult identify(const IdentifyOptions& options, std::FILE* out);

}  // namespace deformable_sim::ros_layer
