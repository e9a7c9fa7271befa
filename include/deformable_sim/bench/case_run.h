// What one run of a reference case measures: its comparisons with the references (one CSV row
// each) and its cost (wall time per step, linear solves, CG iterations, memory).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "deformable_sim/core/bodies/body.h"

namespace deformable_sim::bench {

/// One measured quantity against its references. NaN where a reference does not exist.
struct Comparison {
  std::string case_name;         ///< CSV `case`, e.g. "B_alpha1", "C2_period"
  std::string error_definition;  ///< what `error` and `error_same_mesh` are, with units
  double value = 0.0;            ///< the measured quantity
  double reference_value = 0.0;  ///< the converged 3D value (or the same-mesh run when none)
  double same_mesh_value = 0.0;  ///< CalculiX on the same mesh, or a converged run of ours
  double theory_value = 0.0;     ///< closed-form theory: beam theory, elastica, implicit Euler
  double error = 0.0;            ///< against reference_value: the total error a user sees
  double error_same_mesh = 0.0;  ///< against same_mesh_value: the error of the solver alone
};

struct CaseRun {
  std::vector<Comparison> comparisons;
  /// Wall time of each dynamic tick (all its substeps), or of the whole static solve, ms.
  std::vector<double> step_ms;
  long linear_solves = 0;
  long cg_iterations = 0;
  bool converged = true;         ///< every linear solve (and static iteration) converged
  std::size_t memory_bytes = 0;  ///< heap held by the body and its solver after the run

  /// Takes `substeps` steps of dt / substeps, timing them together as one tick.
  void timeTick(core::Body& body, double dt, int substeps);
};

}  // namespace deformable_sim::bench
