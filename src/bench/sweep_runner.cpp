#include "deformable_sim/bench/sweep_runner.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "deformable_sim/bench/free_vibration.h"
#include "deformable_sim/bench/static_cases.h"
#include "deformable_sim/bench/tip_trajectory.h"

namespace deformable_sim::bench {

namespace {

CaseRun runOnce(const BenchSetting& setting, BenchContext& context) {
  switch (setting.kind) {
    case CaseKind::kLinearStatic:
      return runLinearStatic(setting, context);
    case CaseKind::kLargeDeflection:
      return runLargeDeflection(setting, context);
    case CaseKind::kFreeVibration:
      return runFreeVibration(setting, context);
    case CaseKind::kTrajectory:
      break;
  }
  return runTrajectory(setting, context);
}

}  // namespace

double median(std::vector<double> values) {
  if (values.empty()) return std::nan("");
  const size_t middle = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + middle, values.end());
  if (values.size() % 2 == 1) return values[middle];
  const double upper = values[middle];
  return 0.5 * (upper + *std::max_element(values.begin(), values.begin() + middle));
}

std::vector<BenchRow> runSetting(const BenchSetting& setting, BenchContext& context, int repeat) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const CaseRun first = runOnce(setting, context);
  std::vector<double> step_ms = first.step_ms;
  int runs = 1;
  for (; runs < repeat; ++runs) {
    if (std::chrono::duration<double>(Clock::now() - start).count() > kRepeatBudgetSeconds) break;
    const CaseRun again = runOnce(setting, context);
    step_ms.insert(step_ms.end(), again.step_ms.begin(), again.step_ms.end());
  }
  const core::Mesh& mesh = context.beam(setting.mesh).mesh();
  std::vector<BenchRow> rows;
  for (const Comparison& comparison : first.comparisons) {
    BenchRow row;
    row.setting = setting;
    row.comparison = comparison;
    row.nodes = mesh.numNodes();
    row.elements = mesh.numElements();
    row.ms_per_step_median = median(step_ms);
    row.ms_per_30hz_tick =
        setting.dt_s > 0.0 ? row.ms_per_step_median / (30.0 * setting.dt_s) : std::nan("");
    row.linear_solves = static_cast<double>(first.linear_solves);
    row.iterations_mean = first.linear_solves > 0
                              ? static_cast<double>(first.cg_iterations) / first.linear_solves
                              : 0.0;
    row.memory_bytes = first.memory_bytes;
    row.converged = first.converged;
    row.repeats = runs;
    rows.push_back(row);
  }
  return rows;
}

}  // namespace deformable_sim::bench
