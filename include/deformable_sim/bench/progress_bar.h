// A progress bar on a terminal: redrawn in place on a TTY; in a log (not a TTY), one line each
// time another tenth of the work is done, so CI output stays short.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace deformable_sim::bench {

class ProgressBar {
 public:
  ProgressBar(int total, std::FILE* stream);

  /// `done` of the total are finished; `current` names what runs next.
  void update(int done, const std::string& current);
  /// Ends the bar's line with the total time.
  void finish();

 private:
  int total_;
  std::FILE* stream_;
  bool terminal_;
  int last_tenth_ = -1;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace deformable_sim::bench
