// A finite-element body: every node free, its elements' elasticity through an elastic model (the
// warped stiffness or Neo-Hookean: core/elements/elastic_model.h), the implicit Euler step and
// the quasi-static solve of core/bodies/body.h. Contact reaches its nodes directly: holds within
// a step, nodes held on a plane, forces for the next step only, and the step's own matrix to
// answer impulses.
#pragma once

#include <array>
#include <limits>
#include <memory>
#include <optional>

#include "deformable_sim/core/bodies/body.h"
#include "deformable_sim/core/elements/corotational_elasticity.h"
#include "deformable_sim/core/elements/elastic_model.h"
#include "deformable_sim/core/elements/plasticity.h"

namespace deformable_sim::core {

class FiniteElementBody : public Body {
 public:
  /// Validates the material and the mesh (std::invalid_argument); precomputes every element and
  /// builds the sparsity pattern once.
  FiniteElementBody(std::string name, Mesh mesh, const LinearElasticMaterial& material,
                    const BodyEffects& effects, const SolverSettings& solver);

  /// How often a step may be halved (recursively) when its rotations do not settle: 64 parts;
  /// and how many linear solves a step may take in all, so that its time stays bounded (the kick
  /// of 10^4 weights in the hard cases takes 67, the beam's later flight up to 153 a step).
  static constexpr int kMaxSplits = 6;
  static constexpr int kMaxSolves = 256;

  /// (M + h C + h^2 K') v+ = M v - h (K' x + f0' - f_ext),  x+ = x + h v+, with K' and f0' of
  /// the rotations at x; solved again with those at x+ while the change of rotations would gain
  /// more energy than the step dissipates. Allocates nothing after the first step with the
  /// conjugate gradient solver.
  StepReport step(double dt) override;
  double kineticEnergy() const override;
  /// With the element rotations of the present positions (after a step, or a static solve;
  /// positions moved through mutablePositions() keep the rotations they had).
  double elasticEnergy() const override;
  bool stateIsFinite() const override;
  void undoStep() override;
  std::unique_ptr<ContactParticipant> contactParticipant() override;
  FiniteElementBody* finiteElements() override { return this; }
  const FiniteElementBody* finiteElements() const override { return this; }

  /// The law the body steps through (core/elements/elastic_model.h).
  const ElasticModel& elasticity() const { return *elasticity_; }
  /// The plasticity effect's state, or null when the body has none.
  const Plasticity* plasticity() const { return plasticity_ ? &*plasticity_ : nullptr; }

  /// Direct access for effects applied after a step (contact projection); keep sizes.
  Eigen::VectorXd& mutablePositions() {
    rotations_current_ = false;  // the caller may move nodes
    return x_;
  }
  Eigen::VectorXd& mutableVelocities() { return v_; }
  /// Where the last step began (contact looks there for the face a point came in through).
  const Eigen::VectorXd& stepStart() const { return step_start_; }

  /// Holds one valid node for the next step at `target` (where it is at the step's end), or
  /// lets it go; for contact inside the step loop, so they allocate nothing and do not check the
  /// index.
  void holdNodeAt(int node, const Eigen::Vector3d& target);
  void releaseNode(int node);
  /// Holds a free node on the plane through `target` with unit normal `normal` for the next
  /// step, free along it (a stiff spring along the normal in the solve: contact sliding along an
  /// obstacle); its reaction force is the spring's. Allocates nothing.
  void holdNodeOnPlane(int node, const Eigen::Vector3d& normal, const Eigen::Vector3d& target);
  /// A force on a node in the next step only (the friction on a node held on a plane).
  void addStepForce(int node, const Eigen::Vector3d& force);
  /// Lets the nodes held on planes go and forgets the step forces.
  void releasePlaneHolds();
  /// After a step: x = A^-1 b with the matrix A of its last solve and the constrained nodes'
  /// rows held at zero: how the free nodes' velocities answer impulses b within the step
  /// (contact between bodies). A body that steps with CG factorizes A for these answers, once
  /// per step when first asked: they come many to a step, and a back-substitution is exact and
  /// far cheaper than a CG solve. Allocates nothing once a step has run.
  SolveReport solveLastStep(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  /// Adds to reactionForces() what a velocity change dv of the free nodes (an answer of
  /// solveLastStep) asks of the constrained ones, (A dv) / h there, and of the springs of nodes
  /// held on planes.
  void addConstraintForces(const Eigen::VectorXd& dv);
  /// The nodes held on planes in the coming or last step.
  const std::vector<PlaneHold>& planeHolds() const { return plane_holds_; }
  /// Changes whenever the step's matrix changes by more than its rotations and holds: a new
  /// material, a state set from outside, an undone step, another step length.
  int matrixVersion() const { return matrix_version_; }

 protected:
  void changeMaterial(const LinearElasticMaterial& material) override;
  void assignState(const Eigen::VectorXd& positions, const Eigen::VectorXd& velocities) override;
  StaticReport solveStaticChecked(const StaticSettings& settings) override;
  void holdChanged(int, bool) override { matrixChanged(); }

 private:
  /// The step's matrix is another from now on: the direct solver and solveLastStep factorize
  /// it again when next asked.
  void matrixChanged() {
    matrix_changed_ = true;
    response_factored_ = false;
  }
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
    /// gained - dissipated (J), or Newton's residual (N s)
    double last_excess = std::numeric_limits<double>::infinity();
    double potential = 0.0;  ///< Newton's: the step's potential at its last iterate
  };
  /// Whether the change of rotations gains more energy than the solve dissipated, and by how much.
  struct EnergyCheck {
    bool gains = false;
    double excess = 0.0;  ///< gained - dissipated, J
  };
  /// next_ = A^-1 rhs_ for the step's right-hand side, counted in `report`.
  void solveVelocity(const SystemMatrix& a, double h, bool step_start, StepReport& report);
  /// The rotations (and elastic energy) at the end position x + h v+.
  ElasticModel::Update rotateToEnd(double h, StepReport& report);
  EnergyCheck checkRotationEnergy(const SystemMatrix& a, const ElasticModel::Update& end,
                                  RotationSettling& settling);
  /// For a law that follows the positions (Neo-Hookean): whether another Newton iteration is
  /// needed, because implicit Euler's residual with the law's force at v = next_ is still above
  /// kNewtonTolerance of the step's impulses on some free node, in its part from the law (its
  /// difference from the linearization) or from the solve (unless within CG's tolerance); the
  /// excess is the larger part's largest entry, N s.
  EnergyCheck checkNewtonResidual(const SystemMatrix& a, const ElasticModel::Update& end, double h);
  /// Implicit Euler's incremental potential at the velocity v given the law's energy at x + h v
  /// (with the kinetic energy of the change, the loads' work, the springs of plane holds and
  /// Rayleigh damping, its stiffness part with the linearization's K), J.
  double stepPotential(const Eigen::VectorXd& v, double h, double elastic_energy);
  /// Newton's line search, given the law linearized at the solve's answer (`end`): next_ becomes
  /// the point between the last iterate and that answer, the first of 1, 1/2, 1/4, ... of the
  /// way that lowers the step's potential; returns the law linearized there.
  ElasticModel::Update searchLine(double h, RotationSettling& settling,
                                  const ElasticModel::Update& end, StepReport& report);
  /// Between two solves of a step: a new matrix (the warped law's, or where a law that follows
  /// the positions asks for one), else only the offset of the last linearization.
  void assembleForNextSolve(bool new_matrix, RotationSettling& settling, StepReport& report);
  /// Newton's first iterate: the predicted velocity in next_ or, where that has the higher step
  /// potential, x itself with held nodes at their velocities; the law linearized at the end it
  /// gives (with the matrix of the step's start), and the step's potential there.
  void linearizeAtPrediction(double h, RotationSettling& settling, StepReport& report);
  /// The load on node i in a step: applied, gravity, plastic and the step's own forces.
  Eigen::Vector3d stepLoad(int i) const;
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
                    bool step_start = false, double reference_floor = 0.0, double forcing = 0.0);
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

  /// Whether the law is linearized again wherever the body moves: warping, or a law that must.
  bool followsPositions() const {
    return settings_.effects.warping || elasticity_->followsPositions();
  }

  std::unique_ptr<ElasticModel> elasticity_;
  /// The same object when the law is the warped stiffness (plasticity needs it), else null.
  const CorotationalElasticity* corotational_ = nullptr;
  std::optional<Plasticity> plasticity_;  ///< only with the effect; then also its forces
  Eigen::VectorXd plastic_forces_;
  Eigen::VectorXd step_start_;
  /// The element rotations are those of x_ (warping); K' and f0' are those of the rotations and
  /// the material.
  bool rotations_current_ = false, stiffness_current_ = false;
  int inverted_elements_ = 0;            ///< at x_, when rotations_current_
  double elastic_energy_ = 0.0;          ///< at x_ with its own rotations, when rotations_current_
  int end_inverted_elements_ = 0;        ///< at the end of the step being taken
  Eigen::VectorXd end_positions_;        ///< x + h v+ of the step being taken
  Eigen::VectorXd prescribed_velocity_;  ///< of the constrained nodes in the step being taken
  bool matrix_changed_ = true;           ///< for the direct solver: refactorize on the next solve
  int matrix_version_ = 0;               ///< see matrixVersion()
  double last_mass_coefficient_ = -1.0, last_stiffness_coefficient_ = -1.0;

  std::vector<PlaneHold> plane_holds_;  ///< room for every node, reserved once
  Eigen::VectorXd step_forces_;         ///< forces of the next step only (zero when unused)
  bool has_step_forces_ = false;

  ConjugateGradientSolver cg_;
  std::unique_ptr<DirectSolver> direct_;  ///< only when the scene asks for it
  /// A CG body's factorization for solveLastStep, made when contact between bodies first asks.
  std::unique_ptr<DirectSolver> response_direct_;
  bool response_factored_ = false;
  Eigen::VectorXd rhs_, next_, scratch_;
  Eigen::VectorXd newton_iterate_;   ///< Newton's last iterate (a law that follows positions)
  double load_impulse_ = 0.0;        ///< h |loads| on the free nodes, of the last solve
  Eigen::VectorXd damping_product_;  ///< K v, for the step's potential with stiffness damping
  /// The velocities of the last steps, newest first, for the solver's initial guess.
  std::array<Eigen::VectorXd, 3> v_history_;
  int history_size_ = 0;
  double history_dt_ = 0.0;
};

}  // namespace deformable_sim::core
