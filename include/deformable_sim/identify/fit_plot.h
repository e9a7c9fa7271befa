// The plot of a fit: every observation's measured samples against the simulation with the first
// guess and with the fitted values, over time (drawn by scripts/plot_identify.py, matplotlib).
#pragma once

#include <string>
#include <vector>

#include "deformable_sim/identify/experiment.h"

namespace deformable_sim::identify {

/// The table the script draws: observation, component, time (s), measured, guess, fitted.
void writeFitTable(const Experiment& experiment, const std::vector<double>& guess,
                   const std::vector<double>& fitted, const std::string& csv_path);

/// Writes the table beside `png_path` (.csv) and runs `script` on it, drawing the values or, with
/// `residuals`, simulated minus measured; throws std::runtime_error when the script fails.
void plotFit(const Experiment& experiment, const std::vector<double>& guess,
             const std::vector<double>& fitted, const std::string& png_path,
             const std::string& script, bool residuals = false);

}  // namespace deformable_sim::identify
