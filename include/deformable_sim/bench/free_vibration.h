// Case C2: the beam is released from its static case-A deflection (P = 0.025 N, zero velocity)
// and vibrates freely. The first bending mode's period and its amplitude loss per cycle are fitted
// from the tip's area-mean uz (damped_oscillation.h). With no physical damping, every loss is the
// numerical damping of implicit Euler.
#pragma once

#include "deformable_sim/bench/bench_context.h"
#include "deformable_sim/bench/bench_setting.h"
#include "deformable_sim/bench/case_run.h"

namespace deformable_sim::bench {

/// Two comparisons: "C2_period" (against the converged 3D f1 and the same mesh's lumped-mass f1
/// from CalculiX, with implicit Euler's predicted period as theory) and "C2_damping" (amplitude
/// lost per cycle, against none, with implicit Euler's predicted loss as theory). The tetS meshes
/// are not meant for this case: their split pair of first bending modes beats.
CaseRun runFreeVibration(const BenchSetting& setting, BenchContext& context);

}  // namespace deformable_sim::bench
