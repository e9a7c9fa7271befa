// A deformable body discretised with linear tetrahedra and warped-stiffness elasticity: its state,
// constraints and loads, the linearly implicit Euler step and the quasi-static solve.
#pragma once

#include <Eigen/Core>
#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "deformable_sim/core/corotational_elasticity.h"
#include "deformable_sim/core/linear_solver.h"
#include "deformable_sim/core/material.h"
#include "deformable_sim/core/mesh.h"
#include "deformable_sim/core/plasticity.h"

namespace deformable_sim::core {

/// Rayleigh damping C = mass M + stiffness K'.
struct RayleighDamping {
  double mass = 0.0;       ///< alpha, 1/s
  double stiffness = 0.0;  ///< beta, s
};

/// The effects a body simulates. What is absent is not computed.
struct BodyEffects {
  bool warping = false;                    ///< corotation; false = plain linear FEM (R = I)
  std::optional<Eigen::Vector3d> gravity;  ///< m/s^2
  std::optional<RayleighDamping> damping;
  std::optional<PlasticitySettings> plasticity;  ///< dynamic steps only (not the static solve)
  bool stress_colouring = false;  ///< the surface marker is coloured by strain (ROS layer)
};

/// Quasi-static solve: load ramp and, with warping, the corotational fixed-point iteration.
struct StaticSettings {
  int load_steps = 1;         ///< loads (and prescribed motion) ramped in this many equal steps
  int max_iterations = 200;   ///< corotational iterations per load step
  double tolerance = 1.0e-8;  ///< stop when |dx| <= tolerance * |x - x0|
};

/// Wall time of a step's phases, s (steady clock; for benchmarks and the node's statistics).
struct StepTimes {
  double rotations = 0.0;  ///< element rotations (zero without warping)
  double assembly = 0.0;   ///< K' and f0' (zero when nothing changed: linear FEM)
  double solve = 0.0;      ///< the linear solve, preconditioner set-up included
  double total = 0.0;      ///< the whole step
};

struct StepReport {
  SolveReport solve;
  int inverted_elements = 0;  ///< elements with det F <= 0 at the start of the step
  int contacts = 0;           ///< nodes put back on an obstacle's surface after the step
  /// The step left a non-finite value and was undone by Simulation's watchdog: the body is back
  /// at its last good positions, at rest.
  bool recovered = false;
  StepTimes times;
};

struct StaticReport {
  int iterations = 0;         ///< corotational iterations, all load steps
  int linear_iterations = 0;  ///< CG iterations, all solves
  double last_change = 0.0;   ///< |dx| / |x - x0| of the last iteration
  bool converged = true;
  SolveReport last_solve;
};

class FemBody {
 public:
  /// Validates the material and the mesh (std::invalid_argument), precomputes every element and
  /// builds the sparsity pattern once.
  FemBody(std::string name, Mesh mesh, const LinearElasticMaterial& material,
          const BodyEffects& effects, const SolverSettings& solver);

  const std::string& name() const { return name_; }
  const Mesh& mesh() const { return mesh_; }
  const LinearElasticMaterial& material() const { return material_; }
  const BodyEffects& effects() const { return effects_; }
  const SolverSettings& solverSettings() const { return solver_settings_; }

  /// Changes the material between steps: element stiffnesses and masses are recomputed in place,
  /// the pattern is kept. Throws std::invalid_argument (body unchanged) for a bad material.
  void setMaterial(const LinearElasticMaterial& material);
  /// Changes Rayleigh damping between steps (nullopt: none). Throws for negative coefficients.
  void setDamping(const std::optional<RayleighDamping>& damping);
  /// Changes tolerance and iteration cap between steps (the method stays). Throws for bad values.
  void setSolverLimits(double tolerance, int max_iterations);

  /// Named node groups (indices into the mesh), e.g. from the scene's `groups`.
  void addGroup(const std::string& name, std::vector<int> nodes);
  const std::map<std::string, std::vector<int>>& groups() const { return groups_; }
  int numNodes() const { return mesh_.numNodes(); }

  /// Stacked 3n vectors: positions (m), velocities (m/s), rest positions (m).
  const Eigen::VectorXd& positions() const { return x_; }
  const Eigen::VectorXd& velocities() const { return v_; }
  const Eigen::VectorXd& restPositions() const { return x0_; }
  const std::vector<double>& nodalMasses() const { return mass_; }  ///< kg
  /// Direct access for effects applied after a step (contact projection); keep sizes.
  Eigen::VectorXd& mutablePositions() { return x_; }
  Eigen::VectorXd& mutableVelocities() { return v_; }
  /// Replaces the state (sizes must match); e.g. to start from a given deformation.
  void setState(const Eigen::VectorXd& positions, const Eigen::VectorXd& velocities);

  /// Holds the nodes where they are now (v = 0).
  void fixNodes(const std::vector<int>& nodes);
  /// Prescribes where the nodes are at the end of the next step (v = (target - x) / h); they stay
  /// there afterwards until given another target or released.
  void setNodeTargets(const std::vector<int>& nodes, const std::vector<Eigen::Vector3d>& targets);
  /// Returns the nodes to free motion.
  void releaseNodes(const std::vector<int>& nodes);
  /// Holds one valid node where it is for the next step, or lets it go; for effects inside the
  /// step loop (contact), so they allocate nothing and do not check the index.
  void holdNode(int node);
  void releaseNode(int node);
  bool isConstrained(int node) const { return constrained_[node] != 0; }
  int numConstrained() const;

  /// Applied nodal forces (3n, N); they persist from step to step until changed.
  Eigen::VectorXd& externalForces() { return external_forces_; }
  const Eigen::VectorXd& externalForces() const { return external_forces_; }

  /// One linearly implicit Euler step of length dt (s):
  ///   (M + h C + h^2 K') v+ = M v - h (K' x + f0' - f_ext),  x+ = x + h v+.
  /// Allocates nothing after the first step with the conjugate gradient solver.
  StepReport step(double dt);

  /// Equilibrium under the external forces and gravity: K' x = f_ext - f0', iterated with warping
  /// until the update is below the tolerance. Leaves the body at rest in that state.
  StaticReport solveStatic(const StaticSettings& settings);

  /// Force each constraint exerts on its node in the last step or static solve (3n, N); zero at
  /// free nodes. Their sum balances the loads in equilibrium.
  const Eigen::VectorXd& reactionForces() const { return reaction_; }

  double kineticEnergy() const;  ///< J
  double elasticEnergy() const;  ///< J, with the rotations of the last step

  const CorotationalElasticity& elasticity() const { return elasticity_; }
  /// The plasticity effect's state, or null when the body has none.
  const Plasticity* plasticity() const { return plasticity_ ? &*plasticity_ : nullptr; }

 private:
  /// Updates rotations, K' and f0' from the current positions when they can have changed;
  /// adds the time of each half to `times` when given.
  int updateStiffness(StepTimes* times = nullptr);
  /// x = A^-1 b with prescribed values already in x on constrained nodes.
  SolveReport solve(const SystemMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x);
  SystemMatrix systemMatrix(double mass_coefficient, double stiffness_coefficient) const;
  /// The solver's initial guess for the next velocity (SolverSettings::warm_start).
  void predictVelocity(Eigen::VectorXd& guess) const;

  std::string name_;
  Mesh mesh_;
  std::map<std::string, std::vector<int>> groups_;
  LinearElasticMaterial material_;
  BodyEffects effects_;
  SolverSettings solver_settings_;

  Eigen::VectorXd x0_, x_, v_;
  std::vector<double> mass_;
  CorotationalElasticity elasticity_;
  std::optional<Plasticity> plasticity_;  ///< only with the effect; then also its forces
  Eigen::VectorXd plastic_forces_;
  bool stiffness_assembled_ = false;
  bool matrix_changed_ = true;  ///< for the direct solver: refactorize on the next solve
  double last_mass_coefficient_ = -1.0, last_stiffness_coefficient_ = -1.0;

  ConstraintMask constrained_;
  Eigen::VectorXd targets_;  ///< prescribed positions of constrained nodes
  Eigen::VectorXd external_forces_;
  Eigen::VectorXd reaction_;

  ConjugateGradientSolver cg_;
  std::unique_ptr<DirectSolver> direct_;  ///< only when the scene asks for it
  Eigen::VectorXd rhs_, next_, scratch_;
  /// The velocities of the last steps, newest first, for the solver's initial guess.
  std::array<Eigen::VectorXd, 3> v_history_;
  int history_size_ = 0;
  double history_dt_ = 0.0;
};

}  // namespace deformable_sim::core
