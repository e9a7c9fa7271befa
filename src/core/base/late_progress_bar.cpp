#include "deformable_sim/core/base/late_progress_bar.h"

#include <utility>

namespace deformable_sim::core {

LateProgressBar::LateProgressBar(std::FILE* stream, std::string unit, double delay_s)
    : stream_(stream),
      unit_(std::move(unit)),
      delay_s_(delay_s),
      start_(std::chrono::steady_clock::now()) {}

void LateProgressBar::update(long done, long total, const std::string& current) {
  if (!bar_) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (elapsed < delay_s_) return;
    bar_.emplace(total, stream_, unit_, start_);
  }
  bar_->update(done, current);
}

void LateProgressBar::finish() {
  if (bar_) bar_->finish();
}

}  // namespace deformable_sim::core
