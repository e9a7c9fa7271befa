#include "deformable_sim/core/bodies/whole_body_participant.h"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "deformable_sim/core/base/rotation.h"

namespace deformable_sim::core {

WholeBodyParticipant::WholeBodyParticipant(ReducedBody& body)
    : body_(&body), base_x_(3 * body.numNodes()), base_v_(3 * body.numNodes()) {
  const MassProperties& mass = body.reduced().massProperties();
  rest_centre_ = mass.centre;
  inverse_mass_ = 1.0 / mass.mass;
}

void WholeBodyParticipant::begin(double dt, bool) {
  dt_ = dt;
  const ReducedDynamics& reduced = body_->reduced();
  base_x_ = body_->positions();
  base_v_ = body_->velocities();
  gradient_ = reduced.gradient();
  const MassProperties& mass = reduced.massProperties();
  inverse_moment_ = inverseMoment(mass);
  // A constrained node holds the body: it takes no contact impulse (as a fixed node of a
  // finite-element body does not).
  inverse_mass_ = numConstrained(*body_) > 0 ? 0.0 : 1.0 / mass.mass;
  if (inverse_mass_ == 0.0) inverse_moment_.setZero();
  centre_change_.setZero();
  velocity_change_.setZero();
  gradient_change_.setZero();
  rate_change_.setZero();
}

void WholeBodyParticipant::end() {
  body_->moveBy(centre_change_, gradient_change_, velocity_change_, rate_change_);
}

Eigen::Vector3d WholeBodyParticipant::arm(const SurfacePoint& point) const {
  return point.of(body_->restPositions()) - rest_centre_;
}

Eigen::Vector3d WholeBodyParticipant::position(const SurfacePoint& point) const {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int k = 0; k < point.count; ++k) {
    p += point.weights[k] * base_x_.segment<3>(3 * point.nodes[k]);
  }
  return p + centre_change_ + gradient_change_ * arm(point);
}

Eigen::Vector3d WholeBodyParticipant::velocity(const SurfacePoint& point) const {
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
  for (int k = 0; k < point.count; ++k) {
    u += point.weights[k] * base_v_.segment<3>(3 * point.nodes[k]);
  }
  return u + velocity_change_ + rate_change_ * arm(point);
}

Eigen::Matrix3d WholeBodyParticipant::coupling(const SurfacePoint& at, const SurfacePoint& from,
                                               int) const {
  // A unit impulse along axis d at `from` moves the centre by 1 / m and changes the gradient's
  // rate by gradientChange(); `at` moves with both.
  const Eigen::Vector3d to = arm(at), lever = arm(from);
  Eigen::Matrix3d w;
  for (int d = 0; d < 3; ++d) {
    w.col(d) = inverse_mass_ * Eigen::Vector3d::Unit(d) +
               gradientChange(lever, Eigen::Vector3d::Unit(d)) * to;
  }
  return w;
}

void WholeBodyParticipant::push(const SurfacePoint& point, const Eigen::Vector3d& impulse, bool,
                                int) {
  velocity_change_ += inverse_mass_ * impulse;
  rate_change_ += gradientChange(arm(point), impulse);
  centre_change_ += dt_ * inverse_mass_ * impulse;
  gradient_change_ += gradientChange(arm(point), dt_ * impulse);
}

void WholeBodyParticipant::nudge(const SurfacePoint& point, const Eigen::Vector3d& shift) {
  centre_change_ += inverse_mass_ * shift;
  gradient_change_ += gradientChange(arm(point), shift);
}

// n^T W n is a quadratic form in `normal` (compliance() takes it on sums of axes, not unit).
double RigidParticipant::inverseMass(const SurfacePoint& point,
                                     const Eigen::Vector3d& normal) const {
  const Eigen::Vector3d lever = (gradient_ * arm(point)).cross(normal);
  return inverse_mass_ * normal.squaredNorm() + lever.dot(inverse_moment_ * lever);
}

Eigen::Matrix3d RigidParticipant::inverseMoment(const MassProperties& mass) const {
  return gradient_ * mass.inertia().inverse() * gradient_.transpose();
}

Eigen::Matrix3d RigidParticipant::gradientChange(const Eigen::Vector3d& a,
                                                 const Eigen::Vector3d& amount) const {
  // A turn by I^-1 (r x amount) about the centre, to first order.
  return crossMatrix(inverse_moment_ * (gradient_ * a).cross(amount)) * gradient_;
}

double PseudoRigidParticipant::inverseMass(const SurfacePoint& point,
                                           const Eigen::Vector3d& normal) const {
  const Eigen::Vector3d a = arm(point);
  return (inverse_mass_ + a.dot(inverse_moment_ * a)) * normal.squaredNorm();
}

Eigen::Matrix3d PseudoRigidParticipant::inverseMoment(const MassProperties& mass) const {
  return mass.second_moment.inverse();
}

Eigen::Matrix3d PseudoRigidParticipant::gradientChange(const Eigen::Vector3d& a,
                                                       const Eigen::Vector3d& amount) const {
  return amount * (inverse_moment_ * a).transpose();
}

}  // namespace deformable_sim::core
