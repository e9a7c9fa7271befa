#include "deformable_sim/core/contact.h"

#include <algorithm>

namespace deformable_sim::core {

ContactState::ContactState(int num_nodes)
    : obstacle_(num_nodes, -1),
      point_(num_nodes, Eigen::Vector3d::Zero()),
      normal_(num_nodes, Eigen::Vector3d::Zero()),
      sticking_(num_nodes, 0),
      held_flag_(num_nodes, 0) {
  held_.reserve(num_nodes);
}

void ContactState::forget() {
  std::fill(obstacle_.begin(), obstacle_.end(), -1);
  std::fill(sticking_.begin(), sticking_.end(), 0);
}

void ContactState::resizeForObstacles(size_t count) {
  if (contacts_.size() != count) {  // allocates only when the scene's obstacles change
    contacts_.resize(count);
    patches_.resize(count);
  }
  std::fill(contacts_.begin(), contacts_.end(), ContactLoad{});
  std::fill(patches_.begin(), patches_.end(), Patch{});
}

Eigen::Vector3d ContactState::worldNormal(const std::vector<PlacedShape>& obstacles, int i) const {
  return obstacles[obstacle_[i]].pose.linear() * normal_[i];
}

void ContactState::addForce(int k, const Eigen::Vector3d& at, const Eigen::Vector3d& force) {
  contacts_[k].force += force;
  contacts_[k].torque += at.cross(force);
}

void ContactState::hold(Body& body, const std::vector<PlacedShape>& obstacles) {
  held_.clear();
  for (int i = 0; i < body.numNodes(); ++i) {
    // Only a node that sticks: holding a sliding node would stop it for a whole step, and a
    // frictionless block on a slope would creep down instead of sliding with g sin θ.
    const int k = obstacle_[i];
    if (k < 0 || !sticking_[i] || body.isConstrained(i)) continue;
    body.holdNodeAt(i, obstacles[k].pose * point_[i]);
    held_.push_back(i);
    held_flag_[i] = 1;
  }
}

void ContactState::judgePatches(const Body& body, const std::vector<PlacedShape>& obstacles,
                                const ContactSettings& settings, double dt) {
  // Coulomb's law for the held nodes on one obstacle together: single nodes carry uneven parts
  // of the load, and judging each by itself lets some slip while the body sticks (it creeps) and
  // keeps others held while it slides (it stops).
  const Eigen::VectorXd& reactions = body.reactionForces();
  for (int i : held_) {
    const Eigen::Vector3d n = worldNormal(obstacles, i), r = reactions.segment<3>(3 * i);
    const double pushing = r.dot(n);
    if (!(pushing > 0.0)) continue;
    Patch& patch = patches_[obstacle_[i]];
    patch.pushing += pushing;
    patch.sliding += r - pushing * n;
    patch.mass += body.nodalMasses()[i];
  }
  for (Patch& patch : patches_) {
    const double sliding = patch.sliding.norm(), friction = settings.friction * patch.pushing;
    patch.sticks = sliding <= friction * (1.0 + 1e-12);
    if (patch.sticks) continue;
    // Held, they did not move although the obstacle resisted only `friction` of `sliding`: the
    // velocity the rest would have given them in the step, so that they slide on.
    patch.slip = -(sliding - friction) * dt / patch.mass * patch.sliding / sliding;
    patch.transmitted = friction / sliding;
  }
}

void ContactState::release(Body& body, const std::vector<PlacedShape>& obstacles,
                           const ContactSettings& settings, double dt) {
  resizeForObstacles(obstacles.size());
  judgePatches(body, obstacles, settings, dt);
  // Nodes not held touch only if project() finds them inside again.
  for (int i = 0; i < body.numNodes(); ++i) {
    if (!held_flag_[i]) obstacle_[i] = -1, sticking_[i] = 0;
  }
  for (int i : held_) {
    const int k = obstacle_[i];
    const Patch& patch = patches_[k];
    const Eigen::Vector3d n = worldNormal(obstacles, i);
    const Eigen::Vector3d r = body.reactionForces().segment<3>(3 * i);
    const double pushing = r.dot(n);
    if (pushing > 0.0) {
      addForce(k, body.positions().segment<3>(3 * i),
               pushing * n + patch.transmitted * (r - pushing * n));
      if (!patch.sticks) body.mutableVelocities().segment<3>(3 * i) += patch.slip;
    }
    sticking_[i] = patch.sticks && pushing > 0.0;
    if (!sticking_[i]) obstacle_[i] = -1;  // it lifts off or slides: free
    body.releaseNode(i);
    held_flag_[i] = 0;
  }
  held_.clear();
}

void ContactState::applyFriction(Body& body, int i, const Eigen::Vector3d& obstacle_velocity,
                                 const Eigen::Vector3d& normal, const ContactSettings& settings,
                                 double dt) {
  Eigen::Ref<Eigen::Vector3d> velocity = body.mutableVelocities().segment<3>(3 * i);
  Eigen::Vector3d relative = velocity - obstacle_velocity;
  const double into = -relative.dot(normal);
  if (!(into > 0.0)) {  // resting or leaving: it sticks if it does not slide
    sticking_[i] = sticking_[i] || (relative - relative.dot(normal) * normal).isZero(0.0);
    return;
  }
  relative += into * normal;
  if (settings.friction > 0.0) {
    const double sliding = relative.norm(), slowed = settings.friction * into;
    relative = sliding <= slowed ? Eigen::Vector3d::Zero()
                                 : Eigen::Vector3d(relative * (1.0 - slowed / sliding));
  }
  const Eigen::Vector3d change = obstacle_velocity + relative - velocity;
  velocity += change;
  addForce(obstacle_[i], body.positions().segment<3>(3 * i), body.nodalMasses()[i] * change / dt);
  sticking_[i] = relative.isZero(0.0);
}

int ContactState::project(Body& body, const std::vector<PlacedShape>& obstacles,
                          const std::vector<Eigen::Isometry3d>& start_poses,
                          const ContactSettings& settings, double dt) {
  Eigen::VectorXd& x = body.mutablePositions();
  for (size_t k = 0; k < obstacles.size(); ++k) {
    const PlacedShape& obstacle = obstacles[k];
    const Eigen::Isometry3d to_shape = obstacle.pose.inverse();
    const Eigen::Isometry3d to_start = start_poses[k] * to_shape;  // the point a step ago
    for (int i = 0; i < body.numNodes(); ++i) {
      if (body.isConstrained(i)) continue;
      Eigen::Vector3d surface, normal;
      const double distance =
          signedDistance(obstacle.shape, to_shape * x.segment<3>(3 * i), &surface, &normal);
      if (!(distance < 0.0)) continue;
      contacts_[k].penetration = std::max(contacts_[k].penetration, -distance);
      const Eigen::Vector3d on_surface = obstacle.pose * surface;
      x.segment<3>(3 * i) = on_surface;
      // A node held at its point of this obstacle moved with it: it is inside by round-off only,
      // and still sticks.
      const bool stuck = obstacle_[i] == static_cast<int>(k) && sticking_[i];
      if (obstacle_[i] != static_cast<int>(k)) sticking_[i] = 0;  // a new contact
      obstacle_[i] = static_cast<int>(k);
      point_[i] = surface;
      normal_[i] = normal;
      if (stuck) continue;
      applyFriction(body, i, (on_surface - to_start * on_surface) / dt,
                    obstacle.pose.linear() * normal, settings, dt);
    }
  }
  int touching = 0;
  for (ContactLoad& c : contacts_) c.points = 0, c.centre.setZero();
  for (int i = 0; i < body.numNodes(); ++i) {
    if (obstacle_[i] < 0) continue;
    ++touching;
    ++contacts_[obstacle_[i]].points;
    contacts_[obstacle_[i]].centre += x.segment<3>(3 * i);
  }
  for (ContactLoad& c : contacts_) {
    if (c.points > 0) c.centre /= c.points;
  }
  return touching;
}

}  // namespace deformable_sim::core
