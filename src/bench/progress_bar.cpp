#include "deformable_sim/bench/progress_bar.h"

#include <unistd.h>

#include <algorithm>

namespace deformable_sim::bench {

namespace {

constexpr int kWidth = 30;

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

ProgressBar::ProgressBar(int total, std::FILE* stream)
    : total_(std::max(total, 1)),
      stream_(stream),
      terminal_(isatty(fileno(stream)) != 0),
      start_(std::chrono::steady_clock::now()) {}

void ProgressBar::update(int done, const std::string& current) {
  const double fraction = static_cast<double>(done) / total_;
  const int tenth = static_cast<int>(10 * fraction);
  if (!terminal_ && tenth == last_tenth_) return;
  last_tenth_ = tenth;
  const double elapsed = secondsSince(start_);
  const int filled = static_cast<int>(kWidth * fraction);
  const std::string bar = std::string(filled, '#') + std::string(kWidth - filled, '.');
  char remaining[32] = "";
  if (done > 0)
    std::snprintf(remaining, sizeof remaining, ", ~%.0f s left", elapsed / fraction - elapsed);
  std::fprintf(stream_, "%s[%s] %3.0f%% %d/%d %.0f s%s  %-60.60s%s", terminal_ ? "\r" : "",
               bar.c_str(), 100 * fraction, done, total_, elapsed, remaining, current.c_str(),
               terminal_ ? "" : "\n");
  std::fflush(stream_);
}

void ProgressBar::finish() {
  update(total_, "done");
  if (terminal_) std::fprintf(stream_, "\n");
  std::fprintf(stream_, "%d settings in %.1f s\n", total_, secondsSince(start_));
}

}  // namespace deformable_sim::bench
