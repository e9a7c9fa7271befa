#include "deformable_sim/core/driver/tick_status.h"

namespace deformable_sim::core {

Health health(const TickStatus& status, const Simulation& simulation, int substeps) {
  Health health;
  bool converged = true;
  for (const StepReport& r : status.reports) {
    converged = converged && r.solve.converged;
    health.inverted_elements += r.inverted_elements;
  }
  health.ok = false;
  if (status.recent_recovery) {
    health.summary = "the watchdog undid a step that left a non-finite value";
  } else if (!converged) {
    health.summary = "a solve did not reach its tolerance";
  } else if (!status.paused && status.real_time_factor < 0.9 &&
             simulation.stepCount() > 10 * substeps) {
    health.summary = "cannot keep real time";
  } else {
    health.ok = true;
    health.summary = status.paused ? "paused" : "running";
  }
  return health;
}

}  // namespace deformable_sim::core
