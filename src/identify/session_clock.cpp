#include "deformable_sim/identify/session_clock.h"

#include <algorithm>

namespace deformable_sim::identify {

void SessionClock::add(std::int64_t stamp_ns, double time) {
  sorted_ = sorted_ && (pairs_.empty() || pairs_.back().first <= stamp_ns);
  pairs_.emplace_back(stamp_ns, time);
}

std::optional<double> SessionClock::timeAt(std::int64_t stamp_ns) const {
  if (!sorted_) {
    // Stably: of pairs with one stamp (a command and the state it took effect at) the first.
    std::stable_sort(pairs_.begin(), pairs_.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    sorted_ = true;
  }
  const auto after =
      std::upper_bound(pairs_.begin(), pairs_.end(), stamp_ns,
                       [](std::int64_t stamp, const auto& pair) { return stamp < pair.first; });
  if (pairs_.empty() || (end_ && stamp_ns > *end_)) return std::nullopt;
  if (after == pairs_.begin()) {  // back from the first pair, to the episode's start
    const double back =
        pairs_.front().second - static_cast<double>(pairs_.front().first - stamp_ns) * 1e-9;
    // Within round-off of the start is at it.
    return back > -0.5e-9 ? std::optional<double>(std::max(0.0, back)) : std::nullopt;
  }
  const auto& [stamp, time] = *(after - 1);
  const double on = time + static_cast<double>(stamp_ns - stamp) * 1e-9;
  // Where the reckoning started again, simulated time stood still or crawled meanwhile: no
  // further than the next output shows.
  return after == pairs_.end() ? on : std::min(on, after->second);
}

}  // namespace deformable_sim::identify
