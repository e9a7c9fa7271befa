// The static reference cases, solved with Body::solveStatic: A (linear cantilever, P = 0.025 N)
// and B (large deflection, P = alpha E I / L^2, ramped in 4 load steps).
#pragma once

#include "deformable_sim/bench/bench_context.h"
#include "deformable_sim/bench/bench_setting.h"
#include "deformable_sim/bench/case_run.h"

namespace deformable_sim::bench {

/// Case A. Compares the tip's area-mean uz with the converged 3D value (hex20_L4 C3D20R), with
/// CalculiX C3D4 on the same mesh and with Timoshenko beam theory.
CaseRun runLinearStatic(const BenchSetting& setting, BenchContext& context);

/// Case B at setting.alpha (1 or 2). Compares the tip's area-mean (ux, uz) with the converged 3D
/// value and with CalculiX's NLGEOM C3D4 run on the same mesh; theory: the elastica's uz.
CaseRun runLargeDeflection(const BenchSetting& setting, BenchContext& context);

}  // namespace deformable_sim::bench
