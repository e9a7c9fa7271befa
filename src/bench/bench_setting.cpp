#include "deformable_sim/bench/bench_setting.h"

#include <cmath>
#include <sstream>

namespace deformable_sim::bench {

std::string solverName(const core::SolverSettings& solver) {
  return solver.method == core::SolverSettings::Method::kDirect ? "direct" : "cg";
}

std::string describe(const BenchSetting& setting) {
  std::ostringstream text;
  switch (setting.kind) {
    case CaseKind::kLinearStatic:
      text << "A_static";
      break;
    case CaseKind::kLargeDeflection:
      text << "B_alpha" << setting.alpha;
      break;
    case CaseKind::kFreeVibration:
      text << "C2_vibration";
      break;
    case CaseKind::kTrajectory:
      text << "T_trajectory";
      break;
  }
  text << " " << setting.mesh << (setting.warping ? " warped" : " linear");
  if (setting.dt_s > 0.0) {
    text << " dt 1/" << std::lround(1.0 / setting.dt_s);
    if (setting.substeps > 1) text << "x" << setting.substeps;
  }
  text << " " << solverName(setting.solver);
  if (setting.solver.method == core::SolverSettings::Method::kConjugateGradient) {
    text << " " << setting.solver.tolerance << "/" << setting.solver.max_iterations;
  }
  return text.str();
}

}  // namespace deformable_sim::bench
