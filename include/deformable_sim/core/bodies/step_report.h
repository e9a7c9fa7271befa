// What a body's step and static solve report: their solves, splits, contacts and the wall time
// of their phases; and the settings of the quasi-static solve.
#pragma once

#include "deformable_sim/core/solvers/linear_solver.h"

namespace deformable_sim::core {

/// Quasi-static solve: load ramp and, with warping, the corotational fixed-point iteration.
struct StaticSettings {
  int load_steps = 1;         ///< loads (and prescribed motion) ramped in this many equal steps
  int max_iterations = 200;   ///< corotational iterations per load step
  double tolerance = 1.0e-8;  ///< stop when |dx| <= tolerance * |x - x0|
};

/// Wall time of a step's phases, s (steady clock; for benchmarks and the node's statistics).
struct StepTimes {
  double rotations = 0.0;       ///< element rotations (zero without warping)
  double assembly = 0.0;        ///< K' and f0' (zero when nothing changed: linear FEM)
  double solve = 0.0;           ///< the linear solve, preconditioner set-up included
  double preconditioner = 0.0;  ///< of `solve`: refreshing the preconditioner
  double total = 0.0;           ///< the whole step
  /// Contact, set by ContactStep: with the obstacles (holding before, putting back after the
  /// step), and an equal share of the contact between bodies for each body that takes part.
  double obstacle_contact = 0.0;
  double body_contact = 0.0;
};

struct StepReport {
  SolveReport solve;  ///< of the last solve; iterations summed over all of the step's solves
  /// Solves of the step: one, or more when the change of rotations within it would have gained
  /// energy (SolverSettings::max_rotation_updates).
  int solves = 0;
  /// Times the step (or a part of it) was split in two halves because those solves did not
  /// settle; at most FiniteElementBody::kMaxSplits deep and FiniteElementBody::kMaxSolves solves in
  /// all.
  int splits = 0;
  /// Largest angle an element turned from the last solve's rotations to the step's end, rad.
  double largest_rotation_change = 0.0;
  int inverted_elements = 0;  ///< elements with det F <= 0 at the start of the step
  int contacts = 0;           ///< nodes put back on an obstacle's surface after the step
  /// Contact between bodies: node-triangle and edge-edge pairs with another body that this body is
  /// part of (either side), and with itself; the largest depth such a pair is left at, m.
  int body_contacts = 0;
  int self_contacts = 0;
  double body_penetration = 0.0;
  /// Linear solves contact between bodies took for the body's answers to impulses: three per
  /// node that started touching (core/bodies/implicit_response.h).
  int body_contact_solves = 0;
  /// The step left a non-finite value, or its energy leapt (energy_leapt), and was undone
  /// by Simulation's watchdog: the body is back at its last good positions, at rest.
  bool recovered = false;
  bool energy_leapt = false;
  StepTimes times;
};

struct StaticReport {
  int iterations = 0;         ///< corotational iterations, all load steps
  int linear_iterations = 0;  ///< CG iterations, all solves
  double last_change = 0.0;   ///< |dx| / |x - x0| of the last iteration
  bool converged = true;
  SolveReport last_solve;
};

}  // namespace deformable_sim::core
