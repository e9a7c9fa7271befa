// A progress bar for work that is usually quick: nothing at all until the work has run for a
// while (a second by default), then a ProgressBar. A small grid voxelizes without a line of output;
// a large one shows how far it is instead of stalling in silence.
#pragma once

#include <chrono>
#include <cstdio>
#include <optional>
#include <string>

#include "deformable_sim/core/base/progress_bar.h"

namespace deformable_sim::core {

class LateProgressBar {
 public:
  /// The clock starts here. `unit` names what is counted, as for ProgressBar.
  LateProgressBar(std::FILE* stream, std::string unit, double delay_s = 1.0);

  /// `done` of `total` are finished; `current` names what runs. Draws the bar (made with this
  /// `total`) once delay_s has passed, and from then on.
  void update(long done, long total, const std::string& current = std::string());
  /// Ends the bar's line, if it was shown; otherwise writes nothing.
  void finish();
  bool shown() const { return bar_.has_value(); }

 private:
  std::FILE* stream_;
  std::string unit_;
  double delay_s_;
  std::chrono::steady_clock::time_point start_;
  std::optional<ProgressBar> bar_;
};

}  // namespace deformable_sim::core
