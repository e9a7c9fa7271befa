// How a driver's last tick of a simulation went, and what that says of its health: the node
// publishes both on ~stats and /diagnostics.
#pragma once

#include <string>
#include <vector>

#include "deformable_sim/core/session/simulation.h"

namespace deformable_sim::core {

struct TickStatus {
  bool paused = false;
  double step_time_s = 0.0;  ///< wall time of the tick's steps
  double real_time_factor = 0.0;
  long recoveries = 0;              ///< the watchdog's, all bodies, this episode
  bool recent_recovery = false;     ///< one in the last 2 s
  std::vector<StepReport> reports;  ///< of the last step, per body
};

struct Health {
  bool ok = true;  ///< false: a warning
  std::string summary;
  int inverted_elements = 0;  ///< in the last step, all bodies
};

/// Warns, in this order, of a recent watchdog recovery, a solve that missed its tolerance, and a
/// running simulation slower than 0.9 x real time (after its first ten ticks of `substeps`).
Health health(const TickStatus& status, const Simulation& simulation, int substeps);

}  // namespace deformable_sim::core
