// The clock time of a simulated instant, for the stamps of what the node publishes. In ROS a
// header's stamp says when its data is of (robot_state_publisher stamps tf with the stamp of the
// joint states it came from): a state shows the end of the step that made it, not the moment the
// timer callback that stepped it ran, a jittery fraction of a tick later. Stamped at the
// callback, a re-simulation interpolated at the stamps is a fraction of a step off, which at an
// impact is most of the impact.
//
// An episode's step 0 is at the clock time it starts (the node's start, a reset), and instant t
// (s of simulated time) at start + t, to the nanosecond: a consumer lines up every output with
// the steps, and a replay stamps alike. Simulated time is paced on the clock (TickPacer) but
// stands still in a pause or a wait for tf, and falls behind in a scene slower than real time.
// When an instant stepped to is more than kMostLag off the clock, the reckoning starts again
// there (a new start, the instant at the clock): stamps stay near the clock, where tf's buffers
// and what a robot does meanwhile are. Between such restarts the steps' stamps are exact.
#pragma once

#include <cmath>
#include <cstdint>

namespace deformable_sim::core {

class SimulatedInstants {
 public:
  /// How far an instant stepped to may be off the clock before the reckoning starts again, ns:
  /// TickPacer's kForgiveAfter, past which it drops the ticks owed.
  static constexpr std::int64_t kMostLagNs = 250'000'000;

  /// An episode starts: simulated time 0 is at clock time `now_ns`.
  void startEpisode(std::int64_t now_ns) { start_ns_ = now_ns; }
  /// The bodies stepped to simulated time `time` (s) at clock time `now_ns`: when that instant is
  /// more than kMostLagNs off the clock, it is at the clock from now on. True when it was.
  bool stepped(double time, std::int64_t now_ns) {
    const std::int64_t off = now_ns - stamp(time);
    if (off <= kMostLagNs && off >= -kMostLagNs) return false;
    start_ns_ = now_ns - nanoseconds(time);
    return true;
  }
  /// The clock time of simulated time `time` (s), ns.
  std::int64_t stamp(double time) const { return start_ns_ + nanoseconds(time); }
  /// The clock time of simulated time 0 by the reckoning in force, ns.
  std::int64_t start() const { return start_ns_; }

 private:
  static std::int64_t nanoseconds(double seconds) { return std::llround(seconds * 1e9); }

  std::int64_t start_ns_ = 0;
};

}  // namespace deformable_sim::core
