// How a driver's last tick of a simulation went, and what that says of its health: the node
// publishes both on ~stats and /diagnostics.
#pragma once

#include <string>
#include <vector>

#include "deformable_sim/core/bodies/body.h"

namespace deformable_sim::core {

struct TickStatus {
  bool paused = false;
  double step_time_s = 0.0;  ///< wall time of the tick's steps
  int steps = 0;             ///< steps the tick took
  double real_time_factor = 0.0;
  bool slow = false;                ///< slower than real time for a while (SlowTickWatch)
  long recoveries = 0;              ///< the watchdog's, all bodies, this episode
  bool recent_recovery = false;     ///< one in the last 2 s
  bool recovery_from_leap = false;  ///< the last one undid an energy leap, not a non-finite value
  std::vector<StepReport> reports;  ///< of the last step, per body
};

struct Health {
  bool ok = true;  ///< false: a warning
  std::string summary;
  int inverted_elements = 0;  ///< in the last step, all bodies
};

/// Warns, in this order, of a recent watchdog recovery, a solve that missed its tolerance, and a
/// simulation that has been slower than real time for a while (status.slow), naming where its
/// steps' time goes.
Health health(const TickStatus& status);

/// Where a step's wall time goes: the costliest of elasticity (rotations and assembly), the
/// linear solves, contact with obstacles and contact between bodies, each summed over the bodies,
/// against the tick's mean wall time a step: "contact between bodies 280 of 290 ms a step". With
/// bodies stepping side by side on several threads a sum can exceed the step's wall time.
std::string costliestPart(const TickStatus& status);

}  // namespace deformable_sim::core
