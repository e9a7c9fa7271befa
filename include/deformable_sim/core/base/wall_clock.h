// The steady clock the core times its phases with (benchmarks, the node's statistics).
#pragma once

#include <chrono>

namespace deformable_sim::core {

using WallClock = std::chrono::steady_clock;

/// Seconds of wall time since `start`.
inline double secondsSince(WallClock::time_point start) {
  return std::chrono::duration<double>(WallClock::now() - start).count();
}

}  // namespace deformable_sim::core
