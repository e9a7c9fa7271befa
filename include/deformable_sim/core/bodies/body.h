// A body of a scene: its mesh, state, constraints and loads, the implicit Euler step and
// the quasi-static solve. Its model decides how the mesh moves: finite elements (warped-stiffness
// elasticity, every node free), or a rigid or pseudo-rigid body whose nodes follow a few
// coordinates (core/reduced_dynamics.h) and are computed only when asked for.
#pragma once

#include <Eigen/Core>
#include <array>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "deformable_sim/core/bodies/body_model.h"
#include "deformable_sim/core/bodies/reduced_dynamics.h"
#include "deformable_sim/core/elements/corotational_elasticity.h"
#include "deformable_sim/core/elements/material.h"
#include "deformable_sim/core/elements/mesh.h"
#include "deformable_sim/core/elements/plasticity.h"
#include "deformable_sim/core/solvers/linear_solver.h"

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
  /// The force each constraint exerts (reactionForces()); grasps and contact friction read it.
  bool reactions = true;
  /// The body's own say on the contact effect's `bodies` and `self` (its `effects: {contact:
  /// ...}`); unset: the scene's. Both need the scene's contact effect.
  std::optional<bool> contact_bodies, contact_self;
};

/// How often each effect's code ran: a step counts once per effect it computed. An effect that is
/// off keeps its count at zero.
struct EffectCounters {
  long warping = 0;     ///< element (or body) rotations updated
  long gravity = 0;     ///< gravity added to the loads
  long damping = 0;     ///< Rayleigh damping in the step's matrix
  long plasticity = 0;  ///< plastic flow and its forces
  long reactions = 0;   ///< constraint forces computed
};

/// Names of the effects a body of `model` simulates with `effects`, in the scene file's words
/// (warping, gravity, damping, plasticity, stress_colouring, reactions); contact is the scene's.
std::vector<std::string> effectNames(const BodyEffects& effects, BodyModel model);

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
  /// settle; at most Body::kMaxSplits deep and Body::kMaxSolves solves in all.
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

class Body {
 public:
  /// Validates the material and the mesh (std::invalid_argument). A finite-element body
  /// precomputes every element and builds the sparsity pattern once; a rigid or pseudo-rigid one
  /// integrates its mass properties and allocates nothing per element.
  Body(std::string name, Mesh mesh, const LinearElasticMaterial& material,
       const BodyEffects& effects, const SolverSettings& solver,
       BodyModel model = BodyModel::kFiniteElement);

  BodyModel model() const { return model_; }
  /// The rigid or pseudo-rigid coordinates, or null for a finite-element body.
  const ReducedDynamics* reduced() const { return reduced_ ? &*reduced_ : nullptr; }
  const EffectCounters& effectCounters() const { return counters_; }
  /// Rigid and pseudo-rigid bodies: how often the nodes were computed from the model, and the
  /// nodal forces summed into a resultant. Neither happens in a step, only when asked for or
  /// changed, so a step's work does not depend on the mesh.
  long nodeUpdates() const { return node_updates_; }
  long loadSums() const { return load_sums_; }

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

  /// Stacked 3n vectors: positions (m), velocities (m/s), rest positions (m). A rigid or
  /// pseudo-rigid body computes its nodes here, on the first call after a step.
  const Eigen::VectorXd& positions() const {
    if (nodes_stale_) updateNodes();
    return x_;
  }
  const Eigen::VectorXd& velocities() const {
    if (nodes_stale_) updateNodes();
    return v_;
  }
  const Eigen::VectorXd& restPositions() const { return x0_; }
  const std::vector<double>& nodalMasses() const { return mass_; }  ///< kg
  /// Direct access for effects applied after a step (contact projection); keep sizes. Finite-
  /// element bodies only (std::logic_error otherwise).
  Eigen::VectorXd& mutablePositions();
  Eigen::VectorXd& mutableVelocities();
  /// Rigid and pseudo-rigid bodies: changes the centre, the gradient and their rates by the given
  /// amounts (contact between bodies gathers them); a rigid body's gradient stays a rotation.
  void moveReducedBy(const Eigen::Vector3d& centre, const Eigen::Matrix3d& gradient,
                     const Eigen::Vector3d& velocity, const Eigen::Matrix3d& gradient_rate);
  /// Replaces the state (sizes must match); e.g. to start from a given deformation. A rigid or
  /// pseudo-rigid body takes the motion of its model that fits them best (least squares).
  void setState(const Eigen::VectorXd& positions, const Eigen::VectorXd& velocities);

  /// For Simulation's watchdog: keeps the present positions, tells whether the state is finite,
  /// and returns to the kept positions at rest.
  void rememberState();
  bool stateIsFinite() const;
  void returnToRememberedState();
  /// Finite-element bodies: the positions kept by the last rememberState() (in a Simulation, where
  /// the step began; contact looks there for the face a point came in through).
  const Eigen::VectorXd& rememberedPositions() const { return remembered_positions_; }

  /// Holds the nodes where they are now (v = 0).
  void fixNodes(const std::vector<int>& nodes);
  /// Prescribes where the nodes are at the end of the next step (v = (target - x) / h); they stay
  /// there afterwards until given another target or released.
  void setNodeTargets(const std::vector<int>& nodes, const std::vector<Eigen::Vector3d>& targets);
  /// Returns the nodes to free motion.
  void releaseNodes(const std::vector<int>& nodes);
  /// Holds one valid node where it is for the next step, or lets it go; for effects inside the
  /// step loop (contact), so they allocate nothing (finite-element bodies) and do not check the
  /// index.
  void holdNode(int node);
  /// The same, prescribing where the node is at the end of the next step (a moving contact).
  void holdNodeAt(int node, const Eigen::Vector3d& target);
  void releaseNode(int node);
  bool isConstrained(int node) const { return constrained_[node] != 0; }
  /// Finite-element bodies: holds a free node on the plane through `target` with unit normal
  /// `normal` for the next step, free along it (a stiff spring along the normal in the solve:
  /// contact sliding along an obstacle); its reaction force is the spring's. Allocates nothing.
  void holdNodeOnPlane(int node, const Eigen::Vector3d& normal, const Eigen::Vector3d& target);
  /// Finite-element bodies: a force on a node in the next step only (the friction on a node
  /// held on a plane).
  void addStepForce(int node, const Eigen::Vector3d& force);
  /// Lets the nodes held on planes go and forgets the step forces.
  void releasePlaneHolds();
  /// After a step (finite elements): x = A^-1 b with the matrix A of its last solve and the
  /// constrained nodes' rows held at zero: how the free nodes' velocities answer impulses b
  /// within the step (contact between bodies). A body that steps with CG factorizes A for these
  /// answers, once after each forgetLastStepFactorization(): they come many to a step, and a
  /// back-substitution is exact and far cheaper than a CG solve. Allocates nothing once a step
  /// has run.
  SolveReport solveLastStep(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  /// The step's matrix has changed (a new step): solveLastStep factorizes again when next asked.
  void forgetLastStepFactorization() { response_factored_ = false; }
  /// Adds to reactionForces() what a velocity change dv of the free nodes (an answer of
  /// solveLastStep) asks of the constrained ones, (A dv) / h there, and of the springs of nodes
  /// held on planes.
  void addConstraintForces(const Eigen::VectorXd& dv);
  int numConstrained() const;

  /// Applied nodal forces (3n, N); they persist from step to step until changed. Write them
  /// through the reference before the next step: a rigid or pseudo-rigid body sums them then (do
  /// not keep the reference across steps).
  Eigen::VectorXd& externalForces() {
    loads_stale_ = true;  // a rigid or pseudo-rigid body sums them again before its next step
    return external_forces_;
  }
  const Eigen::VectorXd& externalForces() const { return external_forces_; }

  /// How often a step may be halved (recursively) when its rotations do not settle: 64 parts;
  /// and how many linear solves a step may take in all, so that its time stays bounded (the kick
  /// of 10^4 weights in the hard cases takes 67, the beam's later flight up to 153 a step).
  static constexpr int kMaxSplits = 6;
  static constexpr int kMaxSolves = 256;

  /// One implicit Euler step of length dt (s):
  ///   (M + h C + h^2 K') v+ = M v - h (K' x + f0' - f_ext),  x+ = x + h v+,
  /// with K' and f0' of the rotations at x; solved again with those at x+ while the change of
  /// rotations would gain more energy than the step dissipates. Allocates nothing after the first
  /// step with the conjugate gradient solver.
  StepReport step(double dt);

  /// Equilibrium under the external forces and gravity: K' x = f_ext - f0', iterated with warping
  /// until the update is below the tolerance. Leaves the body at rest in that state.
  StaticReport solveStatic(const StaticSettings& settings);

  /// Force each constraint exerts on its node in the last step or static solve (3n, N); zero at
  /// free nodes. Their sum balances the loads in equilibrium.
  const Eigen::VectorXd& reactionForces() const { return reaction_; }

  double kineticEnergy() const;  ///< J
  /// J, with the element rotations of the present positions (after a step, or a static solve;
  /// positions moved through mutablePositions() keep the rotations they had).
  double elasticEnergy() const;

  /// The elements' elasticity (finite-element bodies; std::logic_error otherwise).
  const CorotationalElasticity& elasticity() const;
  /// The plasticity effect's state, or null when the body has none.
  const Plasticity* plasticity() const { return plasticity_ ? &*plasticity_ : nullptr; }

 private:
  /// Updates rotations, K' and f0' from the current positions when they can have changed;
  /// adds the time of each half to `times` when given. Returns the inverted elements at x_.
  int updateStiffness(StepTimes* times = nullptr);
  /// rhs_ = M v - h (K' x + f0' - f_ext - M g - f_plastic), the step's right-hand side.
  /// Returns h |f_ext + M g + f_plastic| over the free nodes, the impulse of the step's loads.
  double setStepRightHandSide(double h);
  /// Advances the state by h (a step, or a part of one split `depth` times).
  void advance(double h, int depth, StepReport& report);
  /// What advance() keeps track of from one solve of its step to the next.
  struct RotationSettling {
    double start_energy = 0.0;        ///< at x with its own rotations
    double solve_start_energy = 0.0;  ///< at x with the rotations of the solve
    bool product_is_current = false;  ///< scratch_ = A v+ for the last solve
    double last_excess = std::numeric_limits<double>::infinity();  ///< gained - dissipated
  };
  /// Whether the change of rotations gains more energy than the solve dissipated, and by how much.
  struct EnergyCheck {
    bool gains = false;
    double excess = 0.0;  ///< gained - dissipated, J
  };
  /// next_ = A^-1 rhs_ for the step's right-hand side, counted in `report`.
  void solveVelocity(const SystemMatrix& a, double h, bool step_start, StepReport& report);
  /// The rotations (and elastic energy) at the end position x + h v+.
  CorotationalElasticity::RotationUpdate rotateToEnd(double h, StepReport& report);
  EnergyCheck checkRotationEnergy(const SystemMatrix& a,
                                  const CorotationalElasticity::RotationUpdate& end,
                                  RotationSettling& settling);
  /// Reactions, x+ and the velocity history once next_ holds the step's v+.
  void finishAdvance(const SystemMatrix& a, double h, bool product_is_current);
  /// One corotational iteration of solveStatic() towards `fraction` of `load` and of the
  /// constrained nodes' way from `start` to their targets: next_ = the new positions. Returns
  /// |next_ - x|.
  double staticIteration(const SystemMatrix& a, const Eigen::VectorXd& load,
                         const Eigen::VectorXd& start, double fraction, StaticReport& report);
  /// x moves the fraction `relaxation` of the way to next_ (constrained nodes all of it).
  void relaxTowardsNext(double relaxation);
  /// Constraint forces at equilibrium under `load`.
  void setStaticReactions(const Eigen::VectorXd& load);
  /// x = A^-1 b with prescribed values already in x on constrained nodes. `step_start`: the
  /// first solve of a step (ConjugateGradientSolver's sequence of systems); `reference_floor`:
  /// the least norm CG measures its residual against.
  SolveReport solve(const SystemMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                    bool step_start = false, double reference_floor = 0.0);
  SystemMatrix systemMatrix(double mass_coefficient, double stiffness_coefficient) const;
  /// The matrix of a step of h s (damping and the springs of nodes held on planes included).
  SystemMatrix stepMatrix(double h) const;
  /// At a step's start: each plane spring's stiffness (kPlaneStiffness times its node's diagonal
  /// of the step matrix) and the normal velocity that puts its node on its plane in dt.
  void preparePlaneHolds(double dt);
  /// The solver's initial guess for the next velocity (SolverSettings::warm_start).
  void predictVelocity(Eigen::VectorXd& guess) const;
  /// Forgets the velocities and solutions the warm start draws on (the body moved, or came to
  /// rest by other means than a step).
  void restartWarmStart();
  StepReport stepReduced(double dt);
  StaticReport solveStaticReduced(const StaticSettings& settings);
  /// Sums the external forces into load_resultant_ if they may have changed.
  void sumLoads();
  /// Rigid and pseudo-rigid bodies: node positions and velocities from the coordinates.
  void updateNodes() const;
  NodeConstraints nodeConstraints() const;

  std::string name_;
  BodyModel model_;
  Mesh mesh_;
  std::map<std::string, std::vector<int>> groups_;
  LinearElasticMaterial material_;
  BodyEffects effects_;
  SolverSettings solver_settings_;

  Eigen::VectorXd x0_;
  mutable Eigen::VectorXd x_, v_;  ///< of a rigid or pseudo-rigid body: computed when asked for
  mutable bool nodes_stale_ = false;
  mutable long node_updates_ = 0;
  long load_sums_ = 0;
  Eigen::VectorXd remembered_positions_;
  std::vector<double> mass_;
  EffectCounters counters_;
  std::optional<CorotationalElasticity> elasticity_;  ///< finite-element bodies
  std::optional<ReducedDynamics> reduced_;            ///< rigid and pseudo-rigid bodies
  LoadResultant load_resultant_;  ///< external forces summed for reduced_, when they change
  bool loads_stale_ = true;
  std::vector<int> constrained_nodes_;    ///< reduced_ only: the constrained nodes, ascending
  std::optional<Plasticity> plasticity_;  ///< only with the effect; then also its forces
  Eigen::VectorXd plastic_forces_;
  /// The element rotations are those of x_ (warping); K' and f0' are those of the rotations and
  /// the material.
  bool rotations_current_ = false, stiffness_current_ = false;
  int inverted_elements_ = 0;            ///< at x_, when rotations_current_
  double elastic_energy_ = 0.0;          ///< at x_ with its own rotations, when rotations_current_
  int end_inverted_elements_ = 0;        ///< at the end of the step being taken
  Eigen::VectorXd end_positions_;        ///< x + h v+ of the step being taken
  Eigen::VectorXd prescribed_velocity_;  ///< of the constrained nodes in the step being taken
  bool matrix_changed_ = true;           ///< for the direct solver: refactorize on the next solve
  double last_mass_coefficient_ = -1.0, last_stiffness_coefficient_ = -1.0;

  ConstraintMask constrained_;
  Eigen::VectorXd targets_;             ///< prescribed positions of constrained nodes
  std::vector<PlaneHold> plane_holds_;  ///< room for every node, reserved once
  Eigen::VectorXd step_forces_;         ///< forces of the next step only (zero when unused)
  bool has_step_forces_ = false;
  Eigen::VectorXd external_forces_;
  Eigen::VectorXd reaction_;

  ConjugateGradientSolver cg_;
  std::unique_ptr<DirectSolver> direct_;  ///< only when the scene asks for it
  /// A CG body's factorization for solveLastStep, made when contact between bodies first asks.
  std::unique_ptr<DirectSolver> response_direct_;
  bool response_factored_ = false;
  Eigen::VectorXd rhs_, next_, scratch_;
  /// The velocities of the last steps, newest first, for the solver's initial guess.
  std::array<Eigen::VectorXd, 3> v_history_;
  int history_size_ = 0;
  double history_dt_ = 0.0;
};

}  // namespace deformable_sim::core
