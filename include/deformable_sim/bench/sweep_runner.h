// Runs one setting of the sweep, repeatedly for its timing, and turns it into CSV rows.
#pragma once

#include <cstddef>
#include <vector>

#include "deformable_sim/bench/bench_context.h"
#include "deformable_sim/bench/bench_setting.h"
#include "deformable_sim/bench/case_run.h"

namespace deformable_sim::bench {

/// One row of the output: a setting, one of its comparisons, and its cost.
struct BenchRow {
  BenchSetting setting;
  Comparison comparison;
  int nodes = 0;
  int elements = 0;  ///< of the mesh, all types
  /// Median over every timed tick of every repeat (dynamic cases; a tick is dt_s, all substeps),
  /// or over the repeats' whole static solves (static cases), ms.
  double ms_per_step_median = 0.0;
  /// Dynamic cases: the same cost per 1/30 s of simulated time (one tick of a 30 Hz node; 33.3 ms
  /// is a whole core in real time), so that settings with different dt compare. NaN when static.
  double ms_per_30hz_tick = 0.0;
  double iterations_mean = 0.0;  ///< CG iterations per linear solve (0 for the direct solver)
  double linear_solves = 0.0;    ///< per run
  std::size_t memory_bytes = 0;
  bool converged = true;
  int repeats = 0;
};

/// A setting stops repeating once its runs have taken this long: a long run has many ticks (or
/// one long solve) and the median needs no more.
constexpr double kRepeatBudgetSeconds = 3.0;

/// Runs the setting up to `repeat` times (the physics is deterministic: the comparisons are those
/// of the first run, the timing is pooled over all) and returns one row per comparison.
std::vector<BenchRow> runSetting(const BenchSetting& setting, BenchContext& context, int repeat);

/// The median of the values (NaN for none).
double median(std::vector<double> values);

}  // namespace deformable_sim::bench
