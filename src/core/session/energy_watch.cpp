#include "deformable_sim/core/session/energy_watch.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "deformable_sim/core/bodies/finite_element_body.h"
#include "deformable_sim/core/contact/contact_impulses.h"

namespace deformable_sim::core {

EnergyWatch::EnergyWatch(const BodyList& bodies) {
  for (const Body& body : bodies) {
    start_velocities_.emplace_back(3 * body.numNodes());
    start_positions_.emplace_back(3 * body.numNodes());
    end_positions_.emplace_back(3 * body.numNodes());
    end_velocities_.emplace_back(3 * body.numNodes());
    forces_.emplace_back(3 * body.numNodes());
  }
  start_energies_.assign(bodies.size(), 0.0);
  end_energies_.assign(bodies.size(), 0.0);
  judged_.assign(bodies.size(), 0);
}

void EnergyWatch::before(const BodyList& bodies, const std::vector<PlacedShape>& obstacles,
                         double dt) {
  double fastest = 0.0;
  for (size_t b = 0; b < bodies.size(); ++b) {
    const Body& body = bodies[b];
    start_velocities_[b] = body.velocities();
    start_positions_[b] = body.positions();
    // The energy the last judgement found, if the body is still in the state it judged (an
    // elastic energy costs a pass over the elements).
    const bool as_judged = judged_[b] && body.positions() == end_positions_[b] &&
                           body.velocities() == end_velocities_[b];
    start_energies_[b] = as_judged ? end_energies_[b] : energy(body, b);
    judged_[b] = 0;
    for (int i = 0; i < body.numNodes(); ++i) {
      fastest = std::max(fastest, start_velocities_[b].segment<3>(3 * i).norm());
    }
  }
  drive_speed_ =
      std::max({fastest, obstacleSpeed(bodies, obstacles, dt), ContactImpulses::kPushOutSpeed});
  if (obstacle_poses_.size() != obstacles.size()) obstacle_poses_.resize(obstacles.size());
  for (size_t k = 0; k < obstacles.size(); ++k) obstacle_poses_[k] = obstacles[k].pose;
}

double EnergyWatch::obstacleSpeed(const BodyList& bodies, const std::vector<PlacedShape>& obstacles,
                                  double dt) const {
  if (obstacles.empty() || obstacle_poses_.size() != obstacles.size()) return 0.0;
  Eigen::AlignedBox3d box;
  for (const Body& body : bodies) {
    const Eigen::VectorXd& x = body.positions();
    for (int i = 0; i < body.numNodes(); ++i) box.extend(x.segment<3>(3 * i));
  }
  if (box.isEmpty()) return 0.0;
  double fastest = 0.0;
  for (size_t k = 0; k < obstacles.size(); ++k) {
    const Eigen::Isometry3d& now = obstacles[k].pose;
    const Eigen::Isometry3d& last = obstacle_poses_[k];
    // A point p of the obstacle moves by (R_now R_last^T - I)(p - o_now) + (o_now - o_last) in
    // world terms; within the box, |p - o_now| is at most the box's farthest corner.
    const Eigen::AngleAxisd turn(now.linear() * last.linear().transpose());
    double reach = 0.0;
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d corner = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c));
      reach = std::max(reach, (corner - now.translation()).norm());
    }
    const double moved = (now.translation() - last.translation()).norm() +
                         2.0 * std::sin(0.5 * std::abs(turn.angle())) * reach;
    fastest = std::max(fastest, moved / dt);
  }
  return fastest;
}

void EnergyWatch::heldNodes(const BodyList& bodies) {
  for (const Body& body : bodies) {
    const Eigen::VectorXd& v = body.velocities();
    for (int i = 0; i < body.numNodes(); ++i) {
      if (body.isConstrained(i)) drive_speed_ = std::max(drive_speed_, v.segment<3>(3 * i).norm());
    }
  }
}

double EnergyWatch::energy(const Body& body, int b) {
  const FiniteElementBody* elements = body.finiteElements();
  if (!elements || body.settings().effects.warping || elements->elasticity().followsPositions()) {
    return body.kineticEnergy() + body.elasticEnergy();  // a warped body's is kept by its step
  }
  // Linear finite elements: the energy their step conserves, 1/2 u^T K u, by one product with K
  // (elasticEnergy() sums it an element at a time, with a polar decomposition each).
  const ElasticModel& elasticity = elements->elasticity();
  const Eigen::VectorXd& x = body.positions();
  elasticity.stiffness().multiply(x, forces_[b]);
  forces_[b] += elasticity.forceOffset();  // K x + f0 = K (x - x0)
  return body.kineticEnergy() + 0.5 * (x - body.restPositions()).dot(forces_[b]);
}

double EnergyWatch::bound(const Body& body, int b, double dt) const {
  const Eigen::VectorXd& v = body.velocities();
  const Eigen::VectorXd& v0 = start_velocities_[b];
  const Eigen::VectorXd& x = body.positions();
  const Eigen::VectorXd& x0 = start_positions_[b];
  const Eigen::VectorXd& loads = body.externalForces();
  const Eigen::VectorXd& reactions = body.reactionForces();
  const bool has_reactions = body.settings().effects.reactions;
  const std::vector<double>& mass = body.nodalMasses();
  const std::optional<Eigen::Vector3d>& gravity = body.settings().effects.gravity;
  const double g = gravity ? gravity->norm() : 0.0;
  double work = 0.0;
  for (int i = 0; i < body.numNodes(); ++i) {
    if (!(mass[i] > 0.0)) continue;
    // Its momentum change, and a move its velocity does not account for (a point put back out
    // of an obstacle or another body) as the momentum that would have made it.
    const Eigen::Vector3d put_right =
        x.segment<3>(3 * i) - x0.segment<3>(3 * i) - dt * v.segment<3>(3 * i);
    double impulse =
        mass[i] * ((v.segment<3>(3 * i) - v0.segment<3>(3 * i)).norm() + put_right.norm() / dt);
    if (body.isConstrained(i) && !v.segment<3>(3 * i).isZero(0.0)) {
      // A driven node works on its neighbours with its constraint force, whatever its own
      // momentum does; without reactions computed, that work is unknown.
      if (!has_reactions) return std::numeric_limits<double>::infinity();
      impulse = std::max(impulse, dt * reactions.segment<3>(3 * i).norm());
    }
    const double pushed = loads.segment<3>(3 * i).norm() / mass[i] + g;
    work += impulse * (v0.segment<3>(3 * i).norm() + drive_speed_ + dt * pushed);
  }
  return start_energies_[b] + work;
}

bool EnergyWatch::leapt(const Body& body, int b, double dt) {
  double mass = 0.0;
  for (double m : body.nodalMasses()) mass += m;
  const double floor = 0.5 * mass * kFloorSpeed * kFloorSpeed;
  const double now = energy(body, b);
  if (now > kLeap * bound(body, b, dt) + floor) return true;
  judged_[b] = 1;
  end_energies_[b] = now;
  end_positions_[b] = body.positions();
  end_velocities_[b] = body.velocities();
  return false;
}

}  // namespace deformable_sim::core
