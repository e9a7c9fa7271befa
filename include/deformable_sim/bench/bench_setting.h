// One point of the accuracy sweep: a reference case on a mesh, with the knobs that trade accuracy
// for time (warping, step, substeps, solver, tolerance, iteration cap).
#pragma once

#include <string>

#include "deformable_sim/core/solvers/linear_solver.h"

namespace deformable_sim::bench {

enum class CaseKind {
  kLinearStatic,     ///< case A: small tip load, static
  kLargeDeflection,  ///< case B: tip load alpha E I / L^2, static
  kFreeVibration,    ///< case C2: release from the case-A deflection, first bending mode
  kTrajectory,       ///< sudden alpha = 1 tip load from rest: tip path against a converged run
};

struct BenchSetting {
  CaseKind kind = CaseKind::kLinearStatic;
  std::string mesh;    ///< reference mesh id, e.g. "tetU_L2"
  double alpha = 1.0;  ///< kLargeDeflection: load level P L^2 / (E I)
  bool warping = true;
  double dt_s = 0.0;  ///< dynamic cases: the tick (one row's "step"), s; 0 for static cases
  int substeps = 1;   ///< implicit Euler steps per tick, each of dt_s / substeps
  core::SolverSettings solver;
};

/// "direct" or "cg".
std::string solverName(const core::SolverSettings& solver);

/// A short description for the progress bar and error messages, e.g.
/// "B_alpha1 tetU_L2 warped cg 1e-08/1000".
std::string describe(const BenchSetting& setting);

}  // namespace deformable_sim::bench
