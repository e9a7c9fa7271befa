// A progress bar on a terminal: redrawn in place on a TTY; in a log (not a TTY), one line each
// time another tenth of the work is done, so CI output stays short. The accuracy bench shows its
// settings with it, deformable_sim_replay its steps.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace deformable_sim::core {

class ProgressBar {
 public:
  /// `unit` names what is counted, for the closing line ("120 settings in 3.2 s"); times count
  /// from `start` (a bar shown late, once the work has run a while, gives when the work began).
  ProgressBar(long total, std::FILE* stream, std::string unit,
              std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now());

  /// `done` of the total are finished; `current` names what runs next. Cheap enough to call
  /// every step: the bar is redrawn only when what it shows changes (another percent or another
  /// `current`), so a caller that counts thousands of steps does not flood the terminal.
  void update(long done, const std::string& current = std::string());
  /// Ends the bar's line with the total time.
  void finish();

 private:
  long total_;
  std::FILE* stream_;
  std::string unit_;
  bool terminal_;
  int last_percent_ = -1;
  int last_tenth_ = -1;
  std::string last_current_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace deformable_sim::core
