#include "deformable_sim/core/driver/tick_status.h"

#include <array>
#include <cstdio>
#include <utility>

namespace deformable_sim::core {

std::string costliestPart(const TickStatus& status) {
  std::array<std::pair<const char*, double>, 4> parts{{{"elasticity", 0.0},
                                                       {"linear solves", 0.0},
                                                       {"contact with obstacles", 0.0},
                                                       {"contact between bodies", 0.0}}};
  for (const StepReport& r : status.reports) {
    parts[0].second += r.times.rotations + r.times.assembly;
    parts[1].second += r.times.solve;
    parts[2].second += r.times.obstacle_contact;
    parts[3].second += r.times.body_contact;
  }
  std::pair<const char*, double> costliest = parts[0];
  double work = 0.0;
  for (const auto& part : parts) {
    if (part.second > costliest.second) costliest = part;
    work += part.second;
  }
  const double step_s = status.steps > 0 ? status.step_time_s / status.steps : 0.0;
  char text[160];
  // Bodies step side by side, and the parts are the last step's against the tick's mean: their
  // sum may exceed the wall time, and a part is then told against the work, not the wall time.
  if (work > step_s) {
    std::snprintf(text, sizeof text, "%s %.3g of %.3g ms of work a step (%.3g ms wall)",
                  costliest.first, 1e3 * costliest.second, 1e3 * work, 1e3 * step_s);
  } else {
    std::snprintf(text, sizeof text, "%s %.3g of %.3g ms a step", costliest.first,
                  1e3 * costliest.second, 1e3 * step_s);
  }
  return text;
}

Health health(const TickStatus& status) {
  Health health;
  bool converged = true;
  for (const StepReport& r : status.reports) {
    converged = converged && r.solve.converged;
    health.inverted_elements += r.inverted_elements;
  }
  health.ok = false;
  if (status.recent_recovery) {
    health.summary = status.recovery_from_leap
                         ? "the watchdog undid a step whose energy leapt past its inputs"
                         : "the watchdog undid a step that left a non-finite value";
  } else if (!converged) {
    health.summary = "a solve did not reach its tolerance";
  } else if (!status.paused && status.slow) {
    char factor[32];
    std::snprintf(factor, sizeof factor, "%.2g", status.real_time_factor);
    health.summary =
        std::string("cannot keep real time (") + factor + " x real time): " + costliestPart(status);
  } else {
    health.ok = true;
    health.summary = status.paused ? "paused" : "running";
  }
  return health;
}

}  // namespace deformable_sim::core
