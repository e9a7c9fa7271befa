#include "deformable_sim/core/contact_participant.h"

#include <Eigen/Geometry>
#include <Eigen/LU>

namespace deformable_sim::core {

namespace {

Eigen::Matrix3d cross(const Eigen::Vector3d& w) {
  Eigen::Matrix3d m;
  m << 0.0, -w.z(), w.y(), w.z(), 0.0, -w.x(), -w.y(), w.x(), 0.0;
  return m;
}

}  // namespace

ContactParticipant::ContactParticipant(const Body& body)
    : body_(&body), inverse_masses_(body.numNodes(), 0.0) {
  if (!body.reduced()) return;
  base_x_.resize(3 * body.numNodes());
  base_v_.resize(3 * body.numNodes());
  const MassProperties& mass = body.reduced()->massProperties();
  rest_centre_ = mass.centre;
  inverse_mass_ = 1.0 / mass.mass;
}

void ContactParticipant::begin(Body& body) {
  body_ = &body;
  const ReducedDynamics* reduced = body.reduced();
  if (!reduced) {
    x_ = &body.mutablePositions();
    v_ = &body.mutableVelocities();
    for (int i = 0; i < body.numNodes(); ++i) {
      inverse_masses_[i] = body.isConstrained(i) ? 0.0 : 1.0 / body.nodalMasses()[i];
    }
    return;
  }
  base_x_ = body.positions();
  base_v_ = body.velocities();
  gradient_ = reduced->gradient();
  const MassProperties& mass = reduced->massProperties();
  inverse_moment_ =
      reduced->model() == BodyModel::kRigid
          ? Eigen::Matrix3d(gradient_ * mass.inertia().inverse() * gradient_.transpose())
          : Eigen::Matrix3d(mass.second_moment.inverse());
  // A constrained node holds the body: it takes no contact impulse (as a fixed node of a
  // finite-element body does not).
  inverse_mass_ = body.numConstrained() > 0 ? 0.0 : 1.0 / mass.mass;
  if (inverse_mass_ == 0.0) inverse_moment_.setZero();
  centre_change_.setZero();
  velocity_change_.setZero();
  gradient_change_.setZero();
  rate_change_.setZero();
}

void ContactParticipant::end(Body& body) const {
  if (!body.reduced()) return;
  body.moveReducedBy(centre_change_, gradient_change_, velocity_change_, rate_change_);
}

Eigen::Vector3d ContactParticipant::arm(const SurfacePoint& point) const {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  for (int k = 0; k < point.count; ++k) {
    a += point.weights[k] * body_->restPositions().segment<3>(3 * point.nodes[k]);
  }
  return a - rest_centre_;
}

Eigen::Vector3d ContactParticipant::position(const SurfacePoint& point) const {
  const Eigen::VectorXd& x = body_->reduced() ? base_x_ : *x_;
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int k = 0; k < point.count; ++k) p += point.weights[k] * x.segment<3>(3 * point.nodes[k]);
  if (body_->reduced()) p += centre_change_ + gradient_change_ * arm(point);
  return p;
}

Eigen::Vector3d ContactParticipant::velocity(const SurfacePoint& point) const {
  const Eigen::VectorXd& v = body_->reduced() ? base_v_ : *v_;
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
  for (int k = 0; k < point.count; ++k) u += point.weights[k] * v.segment<3>(3 * point.nodes[k]);
  if (body_->reduced()) u += velocity_change_ + rate_change_ * arm(point);
  return u;
}

double ContactParticipant::inverseMass(const SurfacePoint& point,
                                       const Eigen::Vector3d& normal) const {
  if (!body_->reduced()) {
    double w = 0.0;
    for (int k = 0; k < point.count; ++k) {
      w += point.weights[k] * point.weights[k] * inverse_masses_[point.nodes[k]];
    }
    return w;
  }
  const Eigen::Vector3d a = arm(point);
  if (body_->reduced()->model() == BodyModel::kRigid) {
    const Eigen::Vector3d lever = (gradient_ * a).cross(normal);
    return inverse_mass_ + lever.dot(inverse_moment_ * lever);
  }
  return inverse_mass_ + a.dot(inverse_moment_ * a);
}

Eigen::Matrix3d ContactParticipant::gradientChange(const Eigen::Vector3d& a,
                                                   const Eigen::Vector3d& amount) const {
  if (body_->reduced()->model() == BodyModel::kRigid) {
    // A turn by I^-1 (r x amount) about the centre, to first order.
    return cross(inverse_moment_ * (gradient_ * a).cross(amount)) * gradient_;
  }
  return amount * (inverse_moment_ * a).transpose();
}

void ContactParticipant::push(const SurfacePoint& point, const Eigen::Vector3d& impulse) {
  if (!body_->reduced()) {
    for (int k = 0; k < point.count; ++k) {
      const int i = point.nodes[k];
      v_->segment<3>(3 * i) += point.weights[k] * inverse_masses_[i] * impulse;
    }
    return;
  }
  velocity_change_ += inverse_mass_ * impulse;
  rate_change_ += gradientChange(arm(point), impulse);
}

void ContactParticipant::displace(const SurfacePoint& point, const Eigen::Vector3d& shift) {
  if (!body_->reduced()) {
    for (int k = 0; k < point.count; ++k) {
      const int i = point.nodes[k];
      x_->segment<3>(3 * i) += point.weights[k] * inverse_masses_[i] * shift;
    }
    return;
  }
  centre_change_ += inverse_mass_ * shift;
  gradient_change_ += gradientChange(arm(point), shift);
}

}  // namespace deformable_sim::core
