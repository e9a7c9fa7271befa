// The bench's output: one CSV row per setting and comparison. Columns, in this order:
//   case, mesh, elements, warping, dt, substeps, solver, tolerance, max_iterations, error,
//   error_definition, ms_per_step_median, iterations_mean, memory_bytes,
// then error_same_mesh, value, reference_value, same_mesh_value, theory_value, ms_per_30hz_tick,
// nodes, linear_solves, converged, repeats. Fields that do not apply (dt of a static case,
// tolerance of the direct solver, a missing theory) are empty.
#pragma once

#include <ostream>

#include "deformable_sim/bench/sweep_runner.h"

namespace deformable_sim::bench {

void writeCsvHeader(std::ostream& out);
void writeCsvRow(const BenchRow& row, std::ostream& out);

}  // namespace deformable_sim::bench
