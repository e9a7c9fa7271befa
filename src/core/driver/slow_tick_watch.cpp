#include "deformable_sim/core/driver/slow_tick_watch.h"

namespace deformable_sim::core {

void SlowTickWatch::sample(double wall_s, double real_time_factor, bool stepping) {
  if (!stepping || !(real_time_factor < kSlowFactor) || wall_s < since_) {
    clear();
    return;
  }
  if (since_ < 0.0) since_ = wall_s;
  slow_ = wall_s - since_ >= kPatience;
}

void SlowTickWatch::clear() {
  since_ = -1.0;
  slow_ = false;
}

}  // namespace deformable_sim::core
