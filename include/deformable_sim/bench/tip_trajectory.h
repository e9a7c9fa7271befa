// A dynamic large-deflection trajectory: the beam starts at rest and the case-B tip load at
// alpha = 1 (P = 8.33 N, dead load) acts from t = 0. The tip's area-mean displacement is sampled
// every 1/30 s for 1 s (the tip swings down past its static deflection, towards twice it as a
// suddenly loaded spring does, and turns back) and compared with a converged run on the same mesh:
// warped, direct solver, steps of 1/1920 s and 1/960 s combined by Richardson extrapolation
// (implicit Euler's error is first order in the step).
#pragma once

#include "deformable_sim/bench/bench_context.h"
#include "deformable_sim/bench/bench_setting.h"
#include "deformable_sim/bench/case_run.h"

namespace deformable_sim::bench {

/// Time between the compared samples, s; setting.dt_s must divide it.
constexpr double kTrajectorySampleInterval = 1.0 / 30.0;

/// One comparison, "T_trajectory": RMS over the samples of |u - u_ref|, over the largest |u_ref|.
/// The converged run is made on first use for each mesh and kept in the context.
CaseRun runTrajectory(const BenchSetting& setting, BenchContext& context);

}  // namespace deformable_sim::bench
