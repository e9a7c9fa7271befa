#include "deformable_sim/core/contact.h"

namespace deformable_sim::core {

void ContactState::hold(Body& body) {
  const Eigen::VectorXd& v = body.velocities();
  for (int i = 0; i < body.numNodes(); ++i) {
    // Only a node that sticks (friction stopped it, or it was held): holding a sliding node
    // would stop it for a whole step, and a frictionless block on a slope would creep down
    // instead of sliding with g sin θ.
    const Eigen::Vector3d velocity = v.segment<3>(3 * i);
    const bool sticks = (velocity - velocity.dot(normal_[i]) * normal_[i]).isZero(0.0);
    held_[i] = !normal_[i].isZero(0.0) && sticks && !body.isConstrained(i);
    if (held_[i]) body.holdNode(i);
  }
}

void ContactState::release(Body& body, const ContactSettings& settings, double dt) {
  // Coulomb's law for the held nodes together: single nodes of a body carry uneven parts of the
  // load, and judging each by itself lets some slip while the body sticks (it creeps) and keeps
  // others held while it slides (it stops).
  const Eigen::VectorXd& reactions = body.reactionForces();
  double pushing_sum = 0.0, mass_sum = 0.0;
  Eigen::Vector3d sliding_sum = Eigen::Vector3d::Zero();
  for (int i = 0; i < body.numNodes(); ++i) {
    const double pushing = reactions.segment<3>(3 * i).dot(normal_[i]);
    if (!held_[i] || !(pushing > 0.0)) continue;
    pushing_sum += pushing;
    sliding_sum += reactions.segment<3>(3 * i) - pushing * normal_[i];
    mass_sum += body.nodalMasses()[i];
  }
  const double sliding = sliding_sum.norm(), friction = settings.friction * pushing_sum;
  const bool sticks = sliding <= friction * (1.0 + 1e-12);
  // Held, they did not move although the obstacle resisted only `friction` of `sliding`: the
  // velocity the rest would have given them in the step, so that they slide on.
  const Eigen::Vector3d slip =
      sticks ? Eigen::Vector3d::Zero()
             : Eigen::Vector3d(-(sliding - friction) * dt / mass_sum * sliding_sum / sliding);
  for (int i = 0; i < body.numNodes(); ++i) {
    if (!held_[i]) continue;
    const double pushing = reactions.segment<3>(3 * i).dot(normal_[i]);
    if (!(sticks && pushing > 0.0)) normal_[i].setZero();  // it lifts off or slides: free
    if (!sticks && pushing > 0.0) body.mutableVelocities().segment<3>(3 * i) += slip;
    body.releaseNode(i);
    held_[i] = 0;
  }
}

int ContactState::project(Body& body, const std::vector<PlacedShape>& obstacles,
                          const ContactSettings& settings) {
  Eigen::VectorXd& x = body.mutablePositions();
  Eigen::VectorXd& v = body.mutableVelocities();
  for (const PlacedShape& obstacle : obstacles) {
    const Eigen::Isometry3d to_shape = obstacle.pose.inverse();
    for (int i = 0; i < body.numNodes(); ++i) {
      if (body.isConstrained(i)) continue;
      Eigen::Vector3d surface, normal;
      const Eigen::Vector3d p = x.segment<3>(3 * i);
      if (!(signedDistance(obstacle.shape, to_shape * p, &surface, &normal) < 0.0)) continue;
      x.segment<3>(3 * i) = obstacle.pose * surface;
      const Eigen::Vector3d n = obstacle.pose.linear() * normal;
      normal_[i] = n;
      Eigen::Vector3d velocity = v.segment<3>(3 * i);
      const double into = -velocity.dot(n);
      if (into <= 0.0) continue;  // already leaving
      velocity += into * n;
      if (settings.friction > 0.0) {
        const double sliding = velocity.norm();
        const double slowed = settings.friction * into;
        velocity = sliding <= slowed ? Eigen::Vector3d::Zero()
                                     : Eigen::Vector3d(velocity * (1.0 - slowed / sliding));
      }
      v.segment<3>(3 * i) = velocity;
    }
  }
  int touching = 0;
  for (const Eigen::Vector3d& n : normal_) touching += n.isZero(0.0) ? 0 : 1;
  return touching;
}

}  // namespace deformable_sim::core
