// The simulated time of a measurement, from its stamp. The node stamps what it publishes at the
// clock time of the simulated instant it shows: the episode's start plus the simulated time, a
// start that moves on where the node fell behind the clock and started its reckoning again
// (core/driver/simulated_instants.h). The recorded states and commands of the measured episode
// give pairs (stamp, simulated time); a stamp maps through the latest pair at or before it (or
// back from the first), and
// no further than the next pair's time (where the reckoning started again, simulated time stood
// still). A measurement stamped by the node maps to the very instant it shows, one stamped by a
// sensor on the same clock to the instant the node was at then.
#pragma once

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace deformable_sim::identify {

class SessionClock {
 public:
  /// A recorded output stamped `stamp_ns` shows simulated time `time` (s).
  void add(std::int64_t stamp_ns, double time);
  bool empty() const { return pairs_.empty(); }
  /// The session ends at `stamp_ns` (its last recorded state): later stamps are outside it.
  void endAt(std::int64_t stamp_ns) { end_ = stamp_ns; }
  /// The simulated time (s) at clock time `stamp_ns`; before the first pair, back from it; none
  /// outside the session (before the episode's start, simulated time 0, or after its end) or
  /// without pairs.
  std::optional<double> timeAt(std::int64_t stamp_ns) const;

 private:
  /// (stamp, time), ordered by stamp once timeAt() is first asked.
  mutable std::vector<std::pair<std::int64_t, double>> pairs_;
  mutable bool sorted_ = true;
  std::optional<std::int64_t> end_;
};

}  // namespace deformable_sim::identify
