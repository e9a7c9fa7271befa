#include "deformable_sim/core/contact/contact_participant.h"

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

ContactParticipant::ContactParticipant(const Body& body) : body_(&body) {
  if (!body.reduced()) {
    response_.emplace(body.numNodes());
    velocity_change_of_nodes_ = Eigen::VectorXd::Zero(3 * body.numNodes());
    return;
  }
  base_x_.resize(3 * body.numNodes());
  base_v_.resize(3 * body.numNodes());
  const MassProperties& mass = body.reduced()->massProperties();
  rest_centre_ = mass.centre;
  inverse_mass_ = 1.0 / mass.mass;
}

void ContactParticipant::begin(Body& body, double dt, bool new_step) {
  body_ = &body;
  dt_ = dt;
  const ReducedDynamics* reduced = body.reduced();
  if (!reduced) {
    x_ = &body.mutablePositions();
    v_ = &body.mutableVelocities();
    if (new_step) response_->begin(body);
    velocity_change_of_nodes_.setZero();
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

void ContactParticipant::end(Body& body) {
  if (!body.reduced()) {
    *v_ += velocity_change_of_nodes_;
    *x_ += dt_ * velocity_change_of_nodes_;
    body.addConstraintForces(velocity_change_of_nodes_);
    return;
  }
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
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  if (body_->reduced()) {
    for (int k = 0; k < point.count; ++k) {
      p += point.weights[k] * base_x_.segment<3>(3 * point.nodes[k]);
    }
    return p + centre_change_ + gradient_change_ * arm(point);
  }
  // The whole-body answers so far moved the nodes by dt times their velocity change.
  for (int k = 0; k < point.count; ++k) {
    const int i = 3 * point.nodes[k];
    p += point.weights[k] * (x_->segment<3>(i) + dt_ * velocity_change_of_nodes_.segment<3>(i));
  }
  return p;
}

Eigen::Vector3d ContactParticipant::velocity(const SurfacePoint& point) const {
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
  if (body_->reduced()) {
    for (int k = 0; k < point.count; ++k) {
      u += point.weights[k] * base_v_.segment<3>(3 * point.nodes[k]);
    }
    return u + velocity_change_ + rate_change_ * arm(point);
  }
  for (int k = 0; k < point.count; ++k) {
    const int i = 3 * point.nodes[k];
    u += point.weights[k] * (v_->segment<3>(i) + velocity_change_of_nodes_.segment<3>(i));
  }
  return u;
}

double ContactParticipant::inverseMass(const SurfacePoint& point,
                                       const Eigen::Vector3d& normal) const {
  if (!body_->reduced()) {
    Eigen::Matrix3d w = Eigen::Matrix3d::Zero();
    for (int a = 0; a < point.count; ++a) {
      for (int b = 0; b < point.count; ++b) {
        w += point.weights[a] * point.weights[b] * response_->block(point.nodes[a], point.nodes[b]);
      }
    }
    return normal.dot(w * normal);
  }
  // A quadratic form in `normal` (compliance() takes it on sums of axes, which are not unit).
  const Eigen::Vector3d a = arm(point);
  if (body_->reduced()->model() == BodyModel::kRigid) {
    const Eigen::Vector3d lever = (gradient_ * a).cross(normal);
    return inverse_mass_ * normal.squaredNorm() + lever.dot(inverse_moment_ * lever);
  }
  return (inverse_mass_ + a.dot(inverse_moment_ * a)) * normal.squaredNorm();
}

Eigen::Matrix3d ContactParticipant::compliance(const SurfacePoint& point, bool local) const {
  if (local && !body_->reduced()) {
    return nudgeCompliance(point, Eigen::Vector3d::UnitX()) * Eigen::Matrix3d::Identity();
  }
  // The quadratic form n^T W n on the axes and their sums gives W (symmetric).
  Eigen::Matrix3d w;
  for (int a = 0; a < 3; ++a) w(a, a) = inverseMass(point, Eigen::Vector3d::Unit(a));
  for (int a = 0; a < 3; ++a) {
    for (int b = a + 1; b < 3; ++b) {
      const Eigen::Vector3d both = Eigen::Vector3d::Unit(a) + Eigen::Vector3d::Unit(b);
      w(a, b) = w(b, a) = 0.5 * (inverseMass(point, both) - w(a, a) - w(b, b));
    }
  }
  return w;
}

Eigen::Matrix3d ContactParticipant::gradientChange(const Eigen::Vector3d& a,
                                                   const Eigen::Vector3d& amount) const {
  if (body_->reduced()->model() == BodyModel::kRigid) {
    // A turn by I^-1 (r x amount) about the centre, to first order.
    return cross(inverse_moment_ * (gradient_ * a).cross(amount)) * gradient_;
  }
  return amount * (inverse_moment_ * a).transpose();
}

void ContactParticipant::push(const SurfacePoint& point, const Eigen::Vector3d& impulse,
                              bool local) {
  if (local && !body_->reduced()) {
    addLumped(point, impulse, *v_);
    addLumped(point, dt_ * impulse, *x_);
    return;
  }
  if (!body_->reduced()) {
    // Kept apart until end(): one pass over the body per node, where adding the answer to the
    // velocities, the positions and the constraint forces each took three.
    addAnswer(point, impulse, velocity_change_of_nodes_);
    return;
  }
  velocity_change_ += inverse_mass_ * impulse;
  rate_change_ += gradientChange(arm(point), impulse);
  centre_change_ += dt_ * inverse_mass_ * impulse;
  gradient_change_ += gradientChange(arm(point), dt_ * impulse);
}

void ContactParticipant::nudge(const SurfacePoint& point, const Eigen::Vector3d& shift) {
  if (!body_->reduced()) {
    addLumped(point, shift, *x_);
    return;
  }
  centre_change_ += inverse_mass_ * shift;
  gradient_change_ += gradientChange(arm(point), shift);
}

void ContactParticipant::addLumped(const SurfacePoint& point, const Eigen::Vector3d& amount,
                                   Eigen::VectorXd& state) const {
  const double cluster = point.shifts_cells ? clusterMass(point) : 0.0;
  for (int k = 0; k < point.count; ++k) {
    const int i = point.nodes[k];
    if (body_->isConstrained(i)) continue;
    state.segment<3>(3 * i) +=
        point.shifts_cells ? Eigen::Vector3d(amount / cluster)
                           : Eigen::Vector3d(point.weights[k] / body_->nodalMasses()[i] * amount);
  }
}

double ContactParticipant::clusterMass(const SurfacePoint& point) const {
  double mass = 0.0;
  for (int k = 0; k < point.count; ++k) {
    if (!body_->isConstrained(point.nodes[k])) mass += body_->nodalMasses()[point.nodes[k]];
  }
  return mass;
}

double ContactParticipant::nudgeCompliance(const SurfacePoint& point,
                                           const Eigen::Vector3d& normal) const {
  if (body_->reduced()) return inverseMass(point, normal);
  // Node by node: w_i / m_i of the impulse moves node i, and so the point by sum w_i^2 / m_i of
  // it; a point that shifts its cells moves them as one mass, and itself by its free weight.
  if (point.shifts_cells) {
    const double mass = clusterMass(point);
    return mass > 0.0 ? movable(point) / mass : 0.0;
  }
  double w = 0.0;
  for (int k = 0; k < point.count; ++k) {
    const int i = point.nodes[k];
    if (!body_->isConstrained(i))
      w += point.weights[k] * point.weights[k] / body_->nodalMasses()[i];
  }
  return w;
}

double ContactParticipant::movable(const SurfacePoint& point) const {
  if (body_->reduced()) return 1.0;
  double free = 0.0;
  for (int k = 0; k < point.count; ++k) {
    if (!body_->isConstrained(point.nodes[k])) free += point.weights[k];
  }
  return free;
}

void ContactParticipant::addAnswer(const SurfacePoint& point, const Eigen::Vector3d& amount,
                                   Eigen::VectorXd& state) const {
  for (int k = 0; k < point.count; ++k) {
    response_->add(point.nodes[k], point.weights[k] * amount, state);
  }
}

}  // namespace deformable_sim::core
