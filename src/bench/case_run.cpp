#include "deformable_sim/bench/case_run.h"

#include <chrono>

namespace deformable_sim::bench {

void CaseRun::timeTick(core::Body& body, double dt, int substeps) {
  using Clock = std::chrono::steady_clock;
  const double h = dt / substeps;
  const auto start = Clock::now();
  for (int s = 0; s < substeps; ++s) {
    const core::StepReport report = body.step(h);
    ++linear_solves;
    cg_iterations += report.solve.iterations;
    converged = converged && report.solve.converged;
  }
  step_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
}

}  // namespace deformable_sim::bench
