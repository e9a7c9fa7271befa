#include "deformable_sim/core/bodies/elastic_participant.h"

#include <cmath>

namespace deformable_sim::core {

ElasticParticipant::ElasticParticipant(FiniteElementBody& body)
    : body_(&body),
      response_(body),
      velocity_change_of_nodes_(Eigen::VectorXd::Zero(3 * body.numNodes())),
      round_start_(Eigen::VectorXd::Zero(3 * body.numNodes())) {}

void ElasticParticipant::begin(double dt, bool new_step) {
  dt_ = dt;
  x_ = &body_->mutablePositions();
  v_ = &body_->mutableVelocities();
  if (new_step) response_.begin(*body_);
  response_.clearImpulses();
  round_start_ = *x_;
}

void ElasticParticipant::end() {
  response_.velocityChanges(velocity_change_of_nodes_);
  *v_ += velocity_change_of_nodes_;
  *x_ += dt_ * velocity_change_of_nodes_;
  // At most sqrt(3) times the largest component: a bound, not the norm, for its cheapness.
  largest_move_ = std::sqrt(3.0) * (*x_ - round_start_).cwiseAbs().maxCoeff();
  body_->addConstraintForces(velocity_change_of_nodes_);
}

Eigen::Vector3d ElasticParticipant::position(const SurfacePoint& point) const {
  // The whole-body answers so far moved the nodes by dt times their velocity change.
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int k = 0; k < point.count; ++k) {
    const int i = 3 * point.nodes[k];
    p += point.weights[k] * (x_->segment<3>(i) + dt_ * response_.velocityChange(point.nodes[k]));
  }
  return p;
}

Eigen::Vector3d ElasticParticipant::velocity(const SurfacePoint& point) const {
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
  for (int k = 0; k < point.count; ++k) {
    const int i = 3 * point.nodes[k];
    u += point.weights[k] * (v_->segment<3>(i) + response_.velocityChange(point.nodes[k]));
  }
  return u;
}

double ElasticParticipant::inverseMass(const SurfacePoint& point,
                                       const Eigen::Vector3d& normal) const {
  return normal.dot(compliance(point) * normal);
}

Eigen::Matrix3d ElasticParticipant::compliance(const SurfacePoint& point, bool local,
                                               int kept) const {
  if (local) return nudgeCompliance(point, Eigen::Vector3d::UnitX()) * Eigen::Matrix3d::Identity();
  Eigen::Matrix3d w;
  if (kept >= 0 &&
      response_.keptCompliance(kept, point.nodes.data(), point.weights.data(), point.count, w)) {
    return 0.5 * (w + w.transpose());
  }
  w.setZero();
  for (int a = 0; a < point.count; ++a) {
    for (int b = 0; b < point.count; ++b) {
      w += point.weights[a] * point.weights[b] * response_.block(point.nodes[a], point.nodes[b]);
    }
  }
  return 0.5 * (w + w.transpose());  // A^-1 is symmetric; columns kept from other steps nearly
}

Eigen::Matrix3d ElasticParticipant::coupling(const SurfacePoint& at, const SurfacePoint& from,
                                             int from_kept) const {
  Eigen::Matrix3d w;
  // `from`'s kept sum read at `at`'s nodes: its rows there, weighed.
  if (from_kept >= 0 &&
      response_.keptCompliance(from_kept, at.nodes.data(), at.weights.data(), at.count, w)) {
    return w;
  }
  w.setZero();
  for (int a = 0; a < at.count; ++a) {
    for (int b = 0; b < from.count; ++b) {
      w += at.weights[a] * from.weights[b] * response_.block(at.nodes[a], from.nodes[b]);
    }
  }
  return w;
}

int ElasticParticipant::keep(const SurfacePoint& point) {
  // A point of a few nodes is answered as fast node by node, and its sum would only take room
  // in the cache (20 blocks in a row: 30 % slower kept).
  if (point.count <= kFewNodes) return -1;
  return response_.keepPoint(point.nodes.data(), point.weights.data(), point.count);
}

int ElasticParticipant::keepCorner(int id, const SurfacePoint& point) {
  if (point.count <= kFewNodes) return -1;
  return response_.keepCorner(id, point.nodes.data(), point.weights.data(), point.count);
}

void ElasticParticipant::push(const SurfacePoint& point, const Eigen::Vector3d& impulse, bool local,
                              int kept) {
  if (local) {
    addLumped(point, impulse, *v_);
    addLumped(point, dt_ * impulse, *x_);
    return;
  }
  // Gathered until end(), where the whole body takes them at once.
  if (kept >= 0) {
    response_.addPointImpulse(kept, point.nodes.data(), point.weights.data(), point.count, impulse);
    return;
  }
  for (int k = 0; k < point.count; ++k) {
    response_.addImpulse(point.nodes[k], point.weights[k] * impulse);
  }
}

void ElasticParticipant::nudge(const SurfacePoint& point, const Eigen::Vector3d& shift) {
  addLumped(point, shift, *x_);
}

void ElasticParticipant::addLumped(const SurfacePoint& point, const Eigen::Vector3d& amount,
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

double ElasticParticipant::clusterMass(const SurfacePoint& point) const {
  double mass = 0.0;
  for (int k = 0; k < point.count; ++k) {
    if (!body_->isConstrained(point.nodes[k])) mass += body_->nodalMasses()[point.nodes[k]];
  }
  return mass;
}

double ElasticParticipant::nudgeCompliance(const SurfacePoint& point,
                                           const Eigen::Vector3d&) const {
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

double ElasticParticipant::movable(const SurfacePoint& point) const {
  double free = 0.0;
  for (int k = 0; k < point.count; ++k) {
    if (!body_->isConstrained(point.nodes[k])) free += point.weights[k];
  }
  return free;
}

}  // namespace deformable_sim::core
