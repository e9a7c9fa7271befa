// Simulated seconds per second of a clock (the ROS clock, simulated itself under /use_sim_time),
// over the last second of that clock.
#pragma once

#include <deque>
#include <utility>

namespace deformable_sim::core {

class RealTimeFactor {
 public:
  /// Records that the simulation had reached `simulated` s when the clock read `clock` s.
  void sample(double clock, double simulated) {
    if (!samples_.empty() && clock < samples_.back().first) samples_.clear();  // clock went back
    samples_.emplace_back(clock, simulated);
    while (samples_.size() > 2 && clock - samples_.front().first > 1.0) samples_.pop_front();
  }
  /// 0 until the clock has moved.
  double value() const {
    if (samples_.empty()) return 0.0;
    const double elapsed = samples_.back().first - samples_.front().first;
    return elapsed > 0.0 ? (samples_.back().second - samples_.front().second) / elapsed : 0.0;
  }
  void clear() { samples_.clear(); }

 private:
  std::deque<std::pair<double, double>> samples_;  ///< (clock, simulated time)
};

}  // namespace deformable_sim::core
