#include "deformable_sim/core/base/progress_bar.h"

#include <unistd.h>

#include <algorithm>

#include "deformable_sim/core/base/wall_clock.h"

namespace deformable_sim::core {

namespace {

constexpr int kWidth = 30;

}  // namespace

ProgressBar::ProgressBar(long total, std::FILE* stream, std::string unit,
                         std::chrono::steady_clock::time_point start)
    : total_(std::max(total, 1L)),
      stream_(stream),
      unit_(std::move(unit)),
      terminal_(isatty(fileno(stream)) != 0),
      start_(start) {}

void ProgressBar::update(long done, const std::string& current) {
  const double fraction = std::min(static_cast<double>(done) / total_, 1.0);
  const int percent = static_cast<int>(100 * fraction);
  const int tenth = percent / 10;
  if (terminal_ ? percent == last_percent_ && current == last_current_ : tenth == last_tenth_) {
    return;
  }
  last_percent_ = percent;
  last_tenth_ = tenth;
  last_current_ = current;
  const double elapsed = secondsSince(start_);
  const int filled = static_cast<int>(kWidth * fraction);
  const std::string bar = std::string(filled, '#') + std::string(kWidth - filled, '.');
  char remaining[32] = "";
  if (done > 0)
    std::snprintf(remaining, sizeof remaining, ", ~%.0f s left", elapsed / fraction - elapsed);
  std::fprintf(stream_, "%s[%s] %3.0f%% %ld/%ld %.0f s%s  %-60.60s%s", terminal_ ? "\r" : "",
               bar.c_str(), 100 * fraction, done, total_, elapsed, remaining, current.c_str(),
               terminal_ ? "" : "\n");
  std::fflush(stream_);
}

void ProgressBar::finish() {
  update(total_, "done");
  if (terminal_) std::fprintf(stream_, "\n");
  std::fprintf(stream_, "%ld %s in %.1f s\n", total_, unit_.c_str(), secondsSince(start_));
}

}  // namespace deformable_sim::core
