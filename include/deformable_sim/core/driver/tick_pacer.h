// How many ticks' worth of steps a node's timer callback takes, so that simulated time keeps up
// with the clock: one a tick, and after a tick that came late (the step before it ran long,
// another process took the core) the ticks it missed, one more a callback. A timer alone drops
// them: roscpp's starts its schedule again from a callback more than a period late, and a scene
// whose steps take near a period loses a fifth of real time that way. What is owed for longer
// than kForgiveAfter is dropped instead: a scene slower than real time stays slower, and says so
// (its real-time factor), instead of stepping in ever longer bursts.
#pragma once

#include <algorithm>
#include <cmath>

namespace deformable_sim::core {

class TickPacer {
 public:
  /// The most ticks one callback takes, and the debt dropped, s.
  static constexpr int kMostTicks = 2;
  static constexpr double kForgiveAfter = 0.25;

  /// Ticks of `period` s (> 0).
  explicit TickPacer(double period) : period_(period) {}

  /// The ticks to step at a callback at clock time `now` s: the periods since the first
  /// callback, to the nearest (a callback's jitter is not a missed tick), less those stepped.
  /// The first callback, and the first after restart() or a clock that went back (a looped bag,
  /// a test's clock set again), takes one. A callback with nothing owed (a clock coarser than
  /// the timer fires it several times at one time; a timer whose schedule started again half a
  /// period off) takes none, and the schedule moves to it: the next on time takes one.
  int ticksDue(double now) {
    if (!started_ || now < last_) {
      started_ = true;
      origin_ = now;
      stepped_ = 0;
    }
    last_ = now;
    long owed = std::lround((now - origin_) / period_) + 1 - stepped_;
    const long forgive = std::lround(kForgiveAfter / period_);
    if (owed > forgive) {  // long behind: start again from here
      origin_ = now;
      stepped_ = 0;
      owed = 1;
    }
    if (owed <= 0) {
      origin_ = now - static_cast<double>(stepped_ - 1) * period_;
      return 0;
    }
    const int ticks = static_cast<int>(std::min<long>(owed, kMostTicks));
    stepped_ += ticks;
    return ticks;
  }
  /// The next callback starts a new schedule (the node was paused, waited, or changed its rate).
  void restart(double period) {
    period_ = period;
    started_ = false;
  }

 private:
  double period_;
  bool started_ = false;
  double origin_ = 0.0;  ///< clock time of the schedule's first tick, s
  double last_ = 0.0;    ///< of the last callback, s
  long stepped_ = 0;     ///< ticks stepped since then
};

}  // namespace deformable_sim::core
