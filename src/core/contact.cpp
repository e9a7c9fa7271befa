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

void ContactState::release(Body& body, const ContactSettings& settings) {
  for (int i = 0; i < body.numNodes(); ++i) {
    if (!held_[i]) continue;
    const Eigen::Vector3d r = body.reactionForces().segment<3>(3 * i);
    const double pushing = r.dot(normal_[i]);
    const double sliding = (r - pushing * normal_[i]).norm();
    if (!(pushing > 0.0 && sliding <= settings.friction * pushing + 1e-12 * r.norm())) {
      normal_[i].setZero();  // it lifts off or slides: free in the next step
    }
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
