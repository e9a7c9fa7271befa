// Rigid and pseudo-rigid bodies (seed 004): every material point follows x = c + A (X - Xc), with
// A a rotation R (rigid, 6 DOF) or any deformation gradient F (pseudo-rigid, 12 DOF; its elastic
// energy is the material's over the body's volume, with a homogeneous strain). The dynamics works
// on these few coordinates only: a step costs the same for any mesh, plus a little per
// constrained node.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "deformable_sim/core/bodies/body_model.h"
#include "deformable_sim/core/bodies/mass_properties.h"
#include "deformable_sim/core/elements/material.h"

namespace deformable_sim::core {

/// Nodal forces f_i at rest arms a_i = X_i - Xc, summed once whenever they change.
struct LoadResultant {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();         ///< sum f_i, N
  Eigen::Matrix3d first_moment = Eigen::Matrix3d::Zero();  ///< sum f_i a_i^T, N m
};

/// Nodes held at targets: nodes[k] (rest position rest.segment<3>(3 nodes[k])) must be at
/// targets.segment<3>(3 nodes[k]) at the end of the step.
struct NodeConstraints {
  const std::vector<int>* nodes = nullptr;
  const Eigen::VectorXd* rest = nullptr;     ///< 3n rest positions
  const Eigen::VectorXd* targets = nullptr;  ///< 3n targets (read at the constrained nodes)
};

class ReducedDynamics {
 public:
  /// `model` is kRigid or kPseudoRigid; the body starts at rest in its rest shape.
  ReducedDynamics(BodyModel model, const MassProperties& mass,
                  const LinearElasticMaterial& material, bool warping);

  BodyModel model() const { return model_; }
  const MassProperties& massProperties() const { return mass_; }
  /// New mass properties and material (the same body, another density or stiffness).
  void setMaterial(const MassProperties& mass, const LinearElasticMaterial& material);

  const Eigen::Vector3d& centre() const { return centre_; }            ///< c, m
  const Eigen::Matrix3d& gradient() const { return gradient_; }        ///< R or F
  const Eigen::Vector3d& linearVelocity() const { return velocity_; }  ///< of the centre, m/s
  /// Rigid: omega = I^-1 L, rad/s. Pseudo-rigid: the skew part of dF/dt F^-1.
  Eigen::Vector3d angularVelocity() const;
  /// About the centre, N m s (rigid: the state itself, exactly conserved without torque).
  Eigen::Vector3d angularMomentum() const;
  /// dF/dt (pseudo-rigid), or omega x R (rigid).
  Eigen::Matrix3d gradientRate() const;

  /// Position and velocity of the material point at rest arm a = X - Xc.
  Eigen::Vector3d position(const Eigen::Vector3d& arm) const { return centre_ + gradient_ * arm; }
  Eigen::Vector3d velocity(const Eigen::Vector3d& arm) const {
    return velocity_ + gradientRate() * arm;
  }

  /// Sets the coordinates and their rates (rigid: `gradient` is made a proper rotation and only
  /// the angular part of `gradient_rate` R^T is kept).
  void setState(const Eigen::Vector3d& centre, const Eigen::Matrix3d& gradient,
                const Eigen::Vector3d& velocity, const Eigen::Matrix3d& gradient_rate);

  /// One linearly implicit Euler step, as the finite-element body's: loads, gravity (m/s^2) and
  /// Rayleigh damping (alpha on the mass; beta on the stiffness, pseudo-rigid only). Constrained
  /// nodes reach their targets (in the least-squares sense when the targets are not a rigid or
  /// homogeneous motion); `reactions` (3n, when given) gets the force on each of them.
  /// Allocates nothing.
  void step(double h, const LoadResultant& loads, const std::optional<Eigen::Vector3d>& gravity,
            double mass_damping, double stiffness_damping, const NodeConstraints& constraints,
            Eigen::VectorXd* reactions);

  /// Equilibrium with the constraints: Newton iterations on the coordinates until the update is
  /// below `tolerance` (relative). A rigid body only moves onto its constraints. Load that no
  /// constraint or stiffness resists (a free body under gravity) leaves it out of balance: then
  /// it is not converged. Leaves it at rest. Returns the iterations taken, negative when not
  /// converged.
  int solveStatic(const LoadResultant& loads, const std::optional<Eigen::Vector3d>& gravity,
                  const NodeConstraints& constraints, int max_iterations, double tolerance,
                  Eigen::VectorXd& reactions);

  double kineticEnergy() const;  ///< J
  double elasticEnergy() const;  ///< J (zero for a rigid body)
  bool finite() const;           ///< every coordinate and rate is finite
  /// Keeps the present centre and gradient; returns to them at rest (the watchdog's undo).
  void remember();
  void returnToRemembered();

 private:
  using Vector6d = Eigen::Matrix<double, 6, 1>;
  using Vector12d = Eigen::Matrix<double, 12, 1>;
  using Matrix12d = Eigen::Matrix<double, 12, 12>;
  /// What a static solve's last iteration leaves over: the generalized loads and elastic forces
  /// (the first 6 for a rigid body), and J^T J of the constraints.
  struct StaticBalance {
    Vector12d generalized = Vector12d::Zero();
    Matrix12d jtj = Matrix12d::Zero();
  };

  /// The rest arm X - Xc of a constrained node, and how far the node is from its target.
  Eigen::Vector3d restArm(const NodeConstraints& constraints, int node) const;
  Eigen::Vector3d gapToTarget(const NodeConstraints& constraints, int node) const;

  /// step() of each model, with gravity in `force` and damping = 1 + h alpha.
  void stepRigid(double h, const Eigen::Vector3d& force, const Eigen::Matrix3d& first_moment,
                 double damping, const NodeConstraints& constraints, Eigen::VectorXd* reactions);
  void stepPseudoRigid(double h, const Eigen::Vector3d& force, const Eigen::Matrix3d& first_moment,
                       double damping, double stiffness_damping, const NodeConstraints& constraints,
                       Eigen::VectorXd* reactions);
  /// The rigid step's (v, omega) that take the constrained nodes to their targets; `rhs` is the
  /// momentum update, `inertia` the world-frame inertia at the start of the step.
  Vector6d constrainedRigidVelocity(double h, double damping, const Eigen::Matrix3d& inertia,
                                    const Vector6d& rhs, const NodeConstraints& constraints,
                                    Eigen::VectorXd* reactions) const;
  /// Moves the rigid body onto its constraints' targets after the turn of a step.
  void projectRigidOntoTargets(const NodeConstraints& constraints);

  /// One Newton iteration of solveStatic() of each model; returns the update's length (its
  /// gradient part times `radius`), m.
  double staticRigidUpdate(const Eigen::Vector3d& force, const Eigen::Matrix3d& first_moment,
                           const NodeConstraints& constraints, double radius,
                           StaticBalance& balance);
  double staticPseudoRigidUpdate(const Eigen::Vector3d& force, const Eigen::Matrix3d& first_moment,
                                 const NodeConstraints& constraints, double radius,
                                 StaticBalance& balance);
  /// Whether the constraints and the stiffness take up all of the leftover load.
  bool balanced(const StaticBalance& balance, const Eigen::Vector3d& force,
                const Eigen::Matrix3d& first_moment, double radius) const;
  void staticReactions(const NodeConstraints& constraints, const StaticBalance& balance,
                       Eigen::VectorXd& reactions) const;

  Eigen::Vector3d torque(const Eigen::Matrix3d& first_moment) const;
  /// Pseudo-rigid: the first Piola stress times the volume, and its derivative (9x9, column-major
  /// vec(F)), with the rotation of F when warping.
  void elasticForce(Eigen::Matrix3d& force, Eigen::Matrix<double, 9, 9>& stiffness) const;

  BodyModel model_;
  MassProperties mass_;
  double lambda_ = 0.0, mu_ = 0.0;
  bool warping_ = true;
  Eigen::Matrix3d inverse_inertia_ = Eigen::Matrix3d::Identity();  ///< body frame (rigid)

  Eigen::Vector3d centre_;
  Eigen::Matrix3d gradient_ = Eigen::Matrix3d::Identity();
  Eigen::Vector3d velocity_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_momentum_ = Eigen::Vector3d::Zero();  ///< rigid, world frame
  Eigen::Matrix3d gradient_rate_ = Eigen::Matrix3d::Zero();     ///< pseudo-rigid dF/dt
  Eigen::Vector3d remembered_centre_;
  Eigen::Matrix3d remembered_gradient_ = Eigen::Matrix3d::Identity();
};

}  // namespace deformable_sim::core
