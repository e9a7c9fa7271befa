// Lets each time stamp through once: tf warns (TF_REPEATED_DATA) when a frame comes twice with
// one stamp, as it would from a timer that fires several times at one time of a coarse simulated
// clock, or from a recording made under one.
#pragma once

#include <cstdint>

namespace deformable_sim::core {

class OncePerStamp {
 public:
  /// True for a stamp (ns) later than the last one let through, and for one more than a second
  /// earlier (a clock that went back, e.g. a looped bag, starts a new timeline).
  bool accept(std::int64_t stamp_ns) {
    constexpr std::int64_t kNewTimeline = 1000000000;
    if (started_ && stamp_ns <= last_ && stamp_ns >= last_ - kNewTimeline) return false;
    started_ = true;
    last_ = stamp_ns;
    return true;
  }

 private:
  bool started_ = false;
  std::int64_t last_ = 0;
};

}  // namespace deformable_sim::core
