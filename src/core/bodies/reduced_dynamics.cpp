#include "deformable_sim/core/bodies/reduced_dynamics.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "deformable_sim/core/base/rotation.h"

namespace deformable_sim::core {

namespace {

template <int D>
using Vector = Eigen::Matrix<double, D, 1>;
template <int D>
using Matrix = Eigen::Matrix<double, D, D>;
using Vector9d = Eigen::Matrix<double, 9, 1>;

Eigen::Matrix3d skew(const Eigen::Vector3d& w) {
  Eigen::Matrix3d s;
  s << 0.0, -w.z(), w.y(), w.z(), 0.0, -w.x(), -w.y(), w.x(), 0.0;
  return s;
}

// The sum of u_i x v_i given W = sum u_i v_i^T.
Eigen::Vector3d crossOfOuter(const Eigen::Matrix3d& w) {
  return {w(1, 2) - w(2, 1), w(2, 0) - w(0, 2), w(0, 1) - w(1, 0)};
}

Vector9d vec(const Eigen::Matrix3d& m) { return Eigen::Map<const Vector9d>(m.data()); }
Eigen::Matrix3d unvec(const Vector9d& v) { return Eigen::Map<const Eigen::Matrix3d>(v.data()); }

Eigen::Matrix3d rotationOf(const Eigen::Vector3d& angle) {
  const double norm = angle.norm();
  if (norm == 0.0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(norm, angle / norm).toRotationMatrix();
}

// x = A^+ b for symmetric positive semi-definite A: directions whose eigenvalue is below
// `relative` times the largest are left out.
template <int D>
Vector<D> pseudoSolve(const Matrix<D>& a, const Vector<D>& b, double relative) {
  const Eigen::SelfAdjointEigenSolver<Matrix<D>> eigen(a);
  const double cutoff = relative * eigen.eigenvalues().cwiseAbs().maxCoeff();
  Vector<D> x = Vector<D>::Zero();
  for (int k = 0; k < D; ++k) {
    const double value = eigen.eigenvalues()[k];
    if (value > cutoff && value > 0.0) {
      x += eigen.eigenvectors().col(k) * (eigen.eigenvectors().col(k).dot(b) / value);
    }
  }
  return x;
}

constexpr double kConstraintRank = 1e-10;  // relative eigenvalue below which J^T J is singular

// argmin 1/2 u^T A u - r^T u over the u with J^T J u = J^T b: the constraints J u = b, or their
// least-squares best fit when they contradict each other, and A's problem in the directions
// they leave free (A^+ there, for a static solve with unresisted directions).
template <int D>
Vector<D> constrainedSolve(const Matrix<D>& a, const Vector<D>& r, const Matrix<D>& jtj,
                           const Vector<D>& jtb) {
  Vector<D> u = Vector<D>::Zero();
  Matrix<D> free = Matrix<D>::Identity();
  if (jtj.trace() > 0.0) {
    const Eigen::SelfAdjointEigenSolver<Matrix<D>> eigen(jtj);
    const double cutoff = kConstraintRank * eigen.eigenvalues().maxCoeff();
    for (int k = 0; k < D; ++k) {
      if (eigen.eigenvalues()[k] > cutoff) {
        const Vector<D> direction = eigen.eigenvectors().col(k);
        u += direction * (direction.dot(jtb) / eigen.eigenvalues()[k]);
        free -= direction * direction.transpose();
      }
    }
  }
  // The constrained directions get a unit block of A's scale, decoupled from the free ones.
  const double scale = std::max(a.diagonal().cwiseAbs().maxCoeff(), 1e-300);
  const Matrix<D> system = free * a * free + scale * (Matrix<D>::Identity() - free);
  return u + free * pseudoSolve<D>(system, free * (r - a * u), 1e-14);
}

// Node velocity rows: rigid [I, -[r]x] (r = R a), pseudo-rigid [I, a_0 I, a_1 I, a_2 I].
Eigen::Matrix<double, 3, 6> rigidRows(const Eigen::Vector3d& world_arm) {
  Eigen::Matrix<double, 3, 6> j;
  j << Eigen::Matrix3d::Identity(), -skew(world_arm);
  return j;
}

Eigen::Matrix<double, 3, 12> pseudoRigidRows(const Eigen::Vector3d& arm) {
  Eigen::Matrix<double, 3, 12> j;
  j << Eigen::Matrix3d::Identity(), arm.x() * Eigen::Matrix3d::Identity(),
      arm.y() * Eigen::Matrix3d::Identity(), arm.z() * Eigen::Matrix3d::Identity();
  return j;
}

bool hasConstraints(const NodeConstraints& c) { return c.nodes && !c.nodes->empty(); }

// Adds J_k^T J_k and J_k^T b_k of every constrained node k: rows(k) gives its 3 x D rows J_k,
// rhs(k) what they must equal.
template <int D, typename Rows, typename Rhs>
void addConstraintRows(const NodeConstraints& constraints, const Rows& rows, const Rhs& rhs,
                       Matrix<D>& jtj, Vector<D>& jtb) {
  for (int node : *constraints.nodes) {
    const Eigen::Matrix<double, 3, D> j = rows(node);
    jtj += j.transpose() * j;
    jtb += j.transpose() * rhs(node);
  }
}

// Writes rows(k) times the generalized constraint force `multiplier` into the reaction of every
// constrained node k.
template <int D, typename Rows>
void distributeReactions(const NodeConstraints& constraints, const Rows& rows,
                         const Vector<D>& multiplier, Eigen::VectorXd& reactions) {
  for (int node : *constraints.nodes) reactions.segment<3>(3 * node) = rows(node) * multiplier;
}

// The pseudo-rigid body's mass matrix over (c, vec(F)): m I for the centre, J_ij I for F.
Matrix<12> pseudoRigidMassMatrix(double m, const Eigen::Matrix3d& second_moment) {
  Matrix<12> mass_matrix = Matrix<12>::Zero();
  mass_matrix.topLeftCorner<3, 3>() = m * Eigen::Matrix3d::Identity();
  for (int col = 0; col < 3; ++col) {
    for (int row = 0; row < 3; ++row) {
      mass_matrix.block<3, 3>(3 + 3 * row, 3 + 3 * col) =
          second_moment(row, col) * Eigen::Matrix3d::Identity();
    }
  }
  return mass_matrix;
}

Eigen::Matrix3d turned(const Eigen::Vector3d& angle, const Eigen::Matrix3d& rotation) {
  return Eigen::Quaterniond(rotationOf(angle) * rotation).normalized().toRotationMatrix();
}

}  // namespace

ReducedDynamics::ReducedDynamics(BodyModel model, const MassProperties& mass,
                                 const LinearElasticMaterial& material, bool warping)
    : model_(model), warping_(warping), centre_(mass.centre), remembered_centre_(mass.centre) {
  if (model == BodyModel::kFiniteElement) {
    throw std::invalid_argument("reduced dynamics are for rigid and pseudo-rigid bodies");
  }
  setMaterial(mass, material);
}

void ReducedDynamics::setMaterial(const MassProperties& mass,
                                  const LinearElasticMaterial& material) {
  validate(material);
  if (!(mass.mass > 0.0) || !mass.second_moment.allFinite()) {
    throw std::invalid_argument("mesh has no positive volume");
  }
  // Velocities are kept (those of the nodes do not jump): a rigid body's angular momentum is
  // recomputed with the new inertia.
  const Eigen::Vector3d omega =
      model_ == BodyModel::kRigid && mass_.mass > 0.0 ? angularVelocity() : Eigen::Vector3d::Zero();
  mass_ = mass;
  lambda_ = lameLambda(material);
  mu_ = lameMu(material);
  const Eigen::Matrix3d inertia = mass.inertia();
  // A rod of zero thickness has no inertia about its axis: it cannot spin about it, and the
  // inverse leaves that direction out.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(inertia);
  inverse_inertia_.setZero();
  for (int k = 0; k < 3; ++k) {
    if (eigen.eigenvalues()[k] > 1e-12 * eigen.eigenvalues().maxCoeff()) {
      inverse_inertia_ += eigen.eigenvectors().col(k) * eigen.eigenvectors().col(k).transpose() /
                          eigen.eigenvalues()[k];
    }
  }
  angular_momentum_ = gradient_ * inertia * gradient_.transpose() * omega;
}

Eigen::Vector3d ReducedDynamics::angularVelocity() const {
  if (model_ == BodyModel::kRigid) {
    return gradient_ * inverse_inertia_ * gradient_.transpose() * angular_momentum_;
  }
  const Eigen::Matrix3d w = gradient_rate_ * gradient_.inverse();
  return {0.5 * (w(2, 1) - w(1, 2)), 0.5 * (w(0, 2) - w(2, 0)), 0.5 * (w(1, 0) - w(0, 1))};
}

Eigen::Vector3d ReducedDynamics::angularMomentum() const {
  if (model_ == BodyModel::kRigid) return angular_momentum_;
  return crossOfOuter(gradient_ * mass_.second_moment * gradient_rate_.transpose());
}

Eigen::Matrix3d ReducedDynamics::gradientRate() const {
  if (model_ == BodyModel::kRigid) return skew(angularVelocity()) * gradient_;
  return gradient_rate_;
}

void ReducedDynamics::setState(const Eigen::Vector3d& centre, const Eigen::Matrix3d& gradient,
                               const Eigen::Vector3d& velocity,
                               const Eigen::Matrix3d& gradient_rate) {
  centre_ = centre;
  velocity_ = velocity;
  if (model_ == BodyModel::kRigid) {
    gradient_ = extractRotation(gradient);
    const Eigen::Matrix3d spin = gradient_rate * gradient_.transpose();
    const Eigen::Vector3d omega(0.5 * (spin(2, 1) - spin(1, 2)), 0.5 * (spin(0, 2) - spin(2, 0)),
                                0.5 * (spin(1, 0) - spin(0, 1)));
    angular_momentum_ = gradient_ * mass_.inertia() * gradient_.transpose() * omega;
  } else {
    gradient_ = gradient;
    gradient_rate_ = gradient_rate;
  }
}

Eigen::Vector3d ReducedDynamics::torque(const Eigen::Matrix3d& first_moment) const {
  // sum (R a_i) x f_i = the cross of sum (R a_i) f_i^T = R B^T.
  return crossOfOuter(gradient_ * first_moment.transpose());
}

void ReducedDynamics::elasticForce(Eigen::Matrix3d& force,
                                   Eigen::Matrix<double, 9, 9>& stiffness) const {
  const Eigen::Matrix3d r = warping_ ? extractRotation(gradient_) : Eigen::Matrix3d::Identity();
  const double volume = mass_.volume;
  // P = R C[sym(R^T F) - I]: linear in F while R is held (warped stiffness, as the elements').
  const auto unrotated_symmetric = [&](const Eigen::Matrix3d& g) {
    return Eigen::Matrix3d(0.5 * (r.transpose() * g + g.transpose() * r));
  };
  const auto rotated_stress = [&](const Eigen::Matrix3d& strain) {
    return Eigen::Matrix3d(
        r * (2.0 * mu_ * strain + lambda_ * strain.trace() * Eigen::Matrix3d::Identity()));
  };
  force = volume * rotated_stress(unrotated_symmetric(gradient_) - Eigen::Matrix3d::Identity());
  for (int k = 0; k < 9; ++k) {
    Vector9d unit = Vector9d::Zero();
    unit[k] = 1.0;
    stiffness.col(k) = volume * vec(rotated_stress(unrotated_symmetric(unvec(unit))));
  }
}

Eigen::Vector3d ReducedDynamics::restArm(const NodeConstraints& constraints, int node) const {
  return constraints.rest->segment<3>(3 * node) - mass_.centre;
}

Eigen::Vector3d ReducedDynamics::gapToTarget(const NodeConstraints& constraints, int node) const {
  return constraints.targets->segment<3>(3 * node) - position(restArm(constraints, node));
}

void ReducedDynamics::step(double h, const LoadResultant& loads,
                           const std::optional<Eigen::Vector3d>& gravity, double mass_damping,
                           double stiffness_damping, const NodeConstraints& constraints,
                           Eigen::VectorXd* reactions) {
  Eigen::Vector3d force = loads.force;
  if (gravity) force += mass_.mass * *gravity;
  const double damping = 1.0 + h * mass_damping;
  if (model_ == BodyModel::kRigid) {
    stepRigid(h, force, loads.first_moment, damping, constraints, reactions);
  } else {
    stepPseudoRigid(h, force, loads.first_moment, damping, stiffness_damping, constraints,
                    reactions);
  }
}

void ReducedDynamics::stepRigid(double h, const Eigen::Vector3d& force,
                                const Eigen::Matrix3d& first_moment, double damping,
                                const NodeConstraints& constraints, Eigen::VectorXd* reactions) {
  const double m = mass_.mass;
  const bool constrained = hasConstraints(constraints);
  const Eigen::Matrix3d r = gradient_;
  const Eigen::Matrix3d inertia = r * mass_.inertia() * r.transpose();
  const Eigen::Matrix3d inverse = r * inverse_inertia_ * r.transpose();
  // Momentum form: (1 + h alpha) M u+ = M u + h Q, with M u = (m v, L).
  Vector<6> rhs;
  rhs << m * velocity_ + h * force, angular_momentum_ + h * torque(first_moment);
  Vector<6> u;
  u << rhs.head<3>() / (damping * m), inverse * rhs.tail<3>() / damping;
  if (constrained) u = constrainedRigidVelocity(h, damping, inertia, rhs, constraints, reactions);
  velocity_ = u.head<3>();
  Eigen::Vector3d omega = u.tail<3>();
  // Unconstrained, the momentum is the update itself: exactly conserved without torque.
  angular_momentum_ =
      constrained ? Eigen::Vector3d(inertia * omega) : Eigen::Vector3d(rhs.tail<3>() / damping);
  if (!constrained) {
    // Implicit midpoint for the rotation: omega from the inertia at the half-step attitude,
    // which keeps the energy of a free spin (the explicit update gains energy every step).
    for (int iteration = 0; iteration < 4; ++iteration) {
      const Eigen::Matrix3d half = rotationOf(0.5 * h * omega) * r;
      omega = half * inverse_inertia_ * half.transpose() * angular_momentum_;
    }
  }
  gradient_ = turned(h * omega, r);
  centre_ += h * velocity_;
  if (constrained) projectRigidOntoTargets(constraints);
}

ReducedDynamics::Vector6d ReducedDynamics::constrainedRigidVelocity(
    double h, double damping, const Eigen::Matrix3d& inertia, const Vector6d& rhs,
    const NodeConstraints& constraints, Eigen::VectorXd* reactions) const {
  // Each constrained node moves to its target in this step: J_i u = (target - x_i) / h.
  const auto rows = [&](int node) { return rigidRows(gradient_ * restArm(constraints, node)); };
  Matrix<6> a = Matrix<6>::Zero();
  a.topLeftCorner<3, 3>() = damping * mass_.mass * Eigen::Matrix3d::Identity();
  a.bottomRightCorner<3, 3>() = damping * inertia;
  Matrix<6> jtj = Matrix<6>::Zero();
  Vector<6> jtb = Vector<6>::Zero();
  addConstraintRows<6>(
      constraints, rows,
      [&](int node) { return Eigen::Vector3d(gapToTarget(constraints, node) / h); }, jtj, jtb);
  const Vector<6> u = constrainedSolve<6>(a, rhs, jtj, jtb);
  if (reactions) {
    // The generalized constraint force, shared among the nodes with the least norm.
    const Vector<6> multiplier = pseudoSolve<6>(jtj, (a * u - rhs) / h, kConstraintRank);
    distributeReactions<6>(constraints, rows, multiplier, *reactions);
  }
  return u;
}

void ReducedDynamics::projectRigidOntoTargets(const NodeConstraints& constraints) {
  // The velocities meet the constraints to first order; the turn leaves the nodes about
  // h^2 omega^2 r / 2 off their targets. Mass-weighted projections onto them take it back (each
  // is linearized in the rotation: three bring the gap to round-off).
  for (int projection = 0; projection < 3; ++projection) {
    Matrix<6> a = Matrix<6>::Zero();
    a.topLeftCorner<3, 3>() = mass_.mass * Eigen::Matrix3d::Identity();
    a.bottomRightCorner<3, 3>() = gradient_ * mass_.inertia() * gradient_.transpose();
    Matrix<6> jtj = Matrix<6>::Zero();
    Vector<6> jtb = Vector<6>::Zero();
    addConstraintRows<6>(
        constraints, [&](int node) { return rigidRows(gradient_ * restArm(constraints, node)); },
        [&](int node) { return gapToTarget(constraints, node); }, jtj, jtb);
    const Vector<6> delta = constrainedSolve<6>(a, Vector<6>::Zero(), jtj, jtb);
    centre_ += delta.head<3>();
    gradient_ = turned(delta.tail<3>(), gradient_);
  }
}

void ReducedDynamics::stepPseudoRigid(double h, const Eigen::Vector3d& force,
                                      const Eigen::Matrix3d& first_moment, double damping,
                                      double stiffness_damping, const NodeConstraints& constraints,
                                      Eigen::VectorXd* reactions) {
  // (M (1 + h alpha) + (h^2 + h beta) K) u+ = M u + h (Q - V P(F)).
  const bool constrained = hasConstraints(constraints);
  const auto rows = [&](int node) { return pseudoRigidRows(restArm(constraints, node)); };
  Eigen::Matrix3d elastic;
  Eigen::Matrix<double, 9, 9> k;
  elasticForce(elastic, k);
  const Matrix<12> mass_matrix = pseudoRigidMassMatrix(mass_.mass, mass_.second_moment);
  Matrix<12> a = damping * mass_matrix;
  a.bottomRightCorner<9, 9>() += (h * h + h * stiffness_damping) * k;
  Vector<12> u;
  u << velocity_, vec(gradient_rate_);
  Vector<12> rhs = mass_matrix * u;
  rhs.head<3>() += h * force;
  rhs.tail<9>() += h * (vec(first_moment) - vec(elastic));
  Matrix<12> jtj = Matrix<12>::Zero();
  Vector<12> jtb = Vector<12>::Zero();
  if (constrained) {
    // Each constrained node moves to its target in this step: J_i u = (target - x_i) / h.
    addConstraintRows<12>(
        constraints, rows,
        [&](int node) { return Eigen::Vector3d(gapToTarget(constraints, node) / h); }, jtj, jtb);
  }
  u = constrainedSolve<12>(a, rhs, jtj, jtb);
  if (constrained && reactions) {
    const Vector<12> multiplier = pseudoSolve<12>(jtj, (a * u - rhs) / h, kConstraintRank);
    distributeReactions<12>(constraints, rows, multiplier, *reactions);
  }
  velocity_ = u.head<3>();
  gradient_rate_ = unvec(u.tail<9>());
  centre_ += h * velocity_;
  gradient_ += h * gradient_rate_;
}

int ReducedDynamics::solveStatic(const LoadResultant& loads,
                                 const std::optional<Eigen::Vector3d>& gravity,
                                 const NodeConstraints& constraints, int max_iterations,
                                 double tolerance, Eigen::VectorXd& reactions) {
  Eigen::Vector3d force = loads.force;
  if (gravity) force += mass_.mass * *gravity;
  // Lengths of the update: the centre's, and the gradient's times the radius of gyration.
  const double radius = std::sqrt(mass_.second_moment.trace() / mass_.mass);
  velocity_.setZero();
  gradient_rate_.setZero();
  angular_momentum_.setZero();
  int iteration = 0;
  bool converged = false;
  StaticBalance balance;
  while (iteration < max_iterations && !converged) {
    ++iteration;
    balance.jtj.setZero();
    const double change =
        model_ == BodyModel::kRigid
            ? staticRigidUpdate(force, loads.first_moment, constraints, radius, balance)
            : staticPseudoRigidUpdate(force, loads.first_moment, constraints, radius, balance);
    const double displacement = std::hypot(
        (centre_ - mass_.centre).norm(), radius * (gradient_ - Eigen::Matrix3d::Identity()).norm());
    converged = change <= tolerance * std::max(displacement, 1e-12 * radius);
  }
  if (!balanced(balance, force, loads.first_moment, radius)) converged = false;
  if (hasConstraints(constraints)) staticReactions(constraints, balance, reactions);
  return converged ? iteration : -iteration;
}

double ReducedDynamics::staticRigidUpdate(const Eigen::Vector3d& force,
                                          const Eigen::Matrix3d& first_moment,
                                          const NodeConstraints& constraints, double radius,
                                          StaticBalance& balance) {
  Matrix<6> jtj6 = Matrix<6>::Zero();
  Vector<6> jtb = Vector<6>::Zero();
  if (hasConstraints(constraints)) {
    addConstraintRows<6>(
        constraints, [&](int node) { return rigidRows(gradient_ * restArm(constraints, node)); },
        [&](int node) { return gapToTarget(constraints, node); }, jtj6, jtb);
  }
  const Vector<6> delta = constrainedSolve<6>(Matrix<6>::Zero(), Vector<6>::Zero(), jtj6, jtb);
  centre_ += delta.head<3>();
  gradient_ = turned(delta.tail<3>(), gradient_);
  balance.generalized.head<3>() = force;
  balance.generalized.segment<3>(3) = torque(first_moment);
  balance.jtj.topLeftCorner<6, 6>() = jtj6;
  return std::hypot(delta.head<3>().norm(), radius * delta.tail<3>().norm());
}

double ReducedDynamics::staticPseudoRigidUpdate(const Eigen::Vector3d& force,
                                                const Eigen::Matrix3d& first_moment,
                                                const NodeConstraints& constraints, double radius,
                                                StaticBalance& balance) {
  Eigen::Matrix3d elastic;
  Eigen::Matrix<double, 9, 9> k;
  elasticForce(elastic, k);
  Matrix<12> a = Matrix<12>::Zero();
  a.bottomRightCorner<9, 9>() = k;
  Vector<12> rhs;
  rhs << force, vec(first_moment) - vec(elastic);
  Vector<12> jtb = Vector<12>::Zero();
  if (hasConstraints(constraints)) {
    addConstraintRows<12>(
        constraints, [&](int node) { return pseudoRigidRows(restArm(constraints, node)); },
        [&](int node) { return gapToTarget(constraints, node); }, balance.jtj, jtb);
  }
  const Vector<12> delta = constrainedSolve<12>(a, rhs, balance.jtj, jtb);
  centre_ += delta.head<3>();
  gradient_ += unvec(delta.tail<9>());
  elasticForce(elastic, k);
  balance.generalized << force, vec(first_moment) - vec(elastic);
  return std::hypot(delta.head<3>().norm(), radius * delta.tail<9>().norm());
}

bool ReducedDynamics::balanced(const StaticBalance& balance, const Eigen::Vector3d& force,
                               const Eigen::Matrix3d& first_moment, double radius) const {
  // What neither stiffness nor constraints took up: the part of the leftover generalized force
  // outside the constraints' range (torques and first moments per radius of gyration, N).
  const int size = model_ == BodyModel::kRigid ? 6 : 12;
  const Vector<12> taken_up =
      balance.jtj * pseudoSolve<12>(balance.jtj, balance.generalized, kConstraintRank);
  const Vector<12> unbalanced = balance.generalized - taken_up;
  const double load = std::hypot(force.norm(), first_moment.norm() / radius);
  return !(std::hypot(unbalanced.head<3>().norm(),
                      unbalanced.segment(3, size - 3).norm() / radius) > 1e-8 * load);
}

void ReducedDynamics::staticReactions(const NodeConstraints& constraints,
                                      const StaticBalance& balance,
                                      Eigen::VectorXd& reactions) const {
  // The constraints balance what loads and elasticity leave over, where they can.
  if (model_ == BodyModel::kRigid) {
    const Vector<6> multiplier = pseudoSolve<6>(balance.jtj.topLeftCorner<6, 6>(),
                                                -balance.generalized.head<6>(), kConstraintRank);
    distributeReactions<6>(
        constraints, [&](int node) { return rigidRows(gradient_ * restArm(constraints, node)); },
        multiplier, reactions);
  } else {
    const Vector<12> multiplier =
        pseudoSolve<12>(balance.jtj, -balance.generalized, kConstraintRank);
    distributeReactions<12>(
        constraints, [&](int node) { return pseudoRigidRows(restArm(constraints, node)); },
        multiplier, reactions);
  }
}

double ReducedDynamics::kineticEnergy() const {
  double energy = 0.5 * mass_.mass * velocity_.squaredNorm();
  if (model_ == BodyModel::kRigid) return energy + 0.5 * angular_momentum_.dot(angularVelocity());
  return energy + 0.5 * (gradient_rate_ * mass_.second_moment * gradient_rate_.transpose()).trace();
}

double ReducedDynamics::elasticEnergy() const {
  if (model_ == BodyModel::kRigid) return 0.0;
  const Eigen::Matrix3d r = warping_ ? extractRotation(gradient_) : Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d unrotated = r.transpose() * gradient_;
  const Eigen::Matrix3d strain =
      0.5 * (unrotated + unrotated.transpose()) - Eigen::Matrix3d::Identity();
  return mass_.volume *
         (mu_ * strain.squaredNorm() + 0.5 * lambda_ * strain.trace() * strain.trace());
}

bool ReducedDynamics::finite() const {
  return centre_.allFinite() && gradient_.allFinite() && velocity_.allFinite() &&
         angular_momentum_.allFinite() && gradient_rate_.allFinite();
}

void ReducedDynamics::remember() {
  remembered_centre_ = centre_;
  remembered_gradient_ = gradient_;
}

void ReducedDynamics::returnToRemembered() {
  centre_ = remembered_centre_;
  gradient_ = remembered_gradient_;
  velocity_.setZero();
  angular_momentum_.setZero();
  gradient_rate_.setZero();
}

}  // namespace deformable_sim::core
