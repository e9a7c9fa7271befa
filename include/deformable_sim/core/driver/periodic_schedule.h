// When an output published at its own rate is due on ticks of another clock (the node's timer):
// each next time is the previous one plus the period, not the tick's time plus the period, so
// that the mean rate is the one asked for whatever the ticks' phase and jitter.
#pragma once

namespace deformable_sim::core {

class PeriodicSchedule {
 public:
  /// `period` s, > 0.
  explicit PeriodicSchedule(double period) : period_(period) {}

  /// True (and the next time moves on by one period) when `now` has reached the next time. The
  /// first call is always due. After a stall of more than a period, or a clock that went back
  /// (a looped bag), the schedule starts again from `now` instead of catching up in a burst.
  bool due(double now) {
    if (!started_ || now < last_ || now >= next_ + period_) {
      started_ = true;
      last_ = now;
      next_ = now + period_;
      return true;
    }
    last_ = now;
    if (now < next_) return false;
    next_ += period_;
    return true;
  }

 private:
  double period_;
  bool started_ = false;
  double last_ = 0.0;
  double next_ = 0.0;
};

}  // namespace deformable_sim::core
