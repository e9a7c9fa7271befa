// A fit run as the tool runs it, for tests: the fit file written into the recording's folder, the
// printed output kept, a refusal caught.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "deformable_sim/ros/identification.h"

namespace deformable_sim::test {

struct FitRun {
  ros_layer::IdentifyResult result;
  std::string printed;
  std::string refusal;  ///< what identify threw, if it did
};

/// Writes `fit_text` to DIRECTORY/fit.yaml and fits on two threads.
/// With `plot`, draws it (`residuals`: simulated minus measured).
FitRun runFit(const std::filesystem::path& directory, const std::string& fit_text,
              int max_iterations = 30, const std::string& plot = "", bool residuals = false);

/// The fit converged, and its i-th value is within `relative[i]` of `truth[i]` and within 3 sigma.
void expectFitted(const FitRun& run, const std::vector<double>& truth,
                  const std::vector<double>& relative);

/// `text` with its first `from` replaced by `to` (a test failure when there is none).
std::string replaced(std::string text, const std::string& from, const std::string& to);

}  // namespace deformable_sim::test
