#include "deformable_sim/core/contact/contact_impulses.h"

#include <algorithm>
#include <cmath>

namespace deformable_sim::core {

ContactImpulses::ContactImpulses(BodyList& bodies, const ContactSettings& settings,
                                 const std::vector<bool>& takes_part)
    : settings_(settings),
      surfaces_(bodies.size()),
      participants_(bodies.size()),
      corners_(bodies.size()),
      margins_(bodies.size(), 0.0),
      body_start_(bodies.size() + 1, 0),
      loads_(bodies.size()),
      warm_(bodies.size()) {
  for (size_t b = 0; b < bodies.size(); ++b) {
    if (!takes_part[b]) continue;
    Body& body = bodies[b];
    surfaces_[b].emplace(body.mesh(), body.positions(), false);
    participants_[b] = body.contactParticipant();
    corners_[b].resize(body.numNodes());
    margins_[b] = kMarginOfSize * surfaces_[b]->size();
    warm_[b].resize(body.numNodes());
  }
}

void ContactImpulses::embed(int b, const EmbeddedSurface& surface, const Body& body) {
  if (!surfaces_[b]) return;
  surfaces_[b].emplace(surface, body.positions());
  margins_[b] = kMarginOfSize * surfaces_[b]->size();
  const size_t corners = surface.numVertices();
  corners_[b].resize(corners);
  warm_[b].assign(corners, Warm{});
}

void ContactImpulses::forget(int b) {
  for (Warm& w : warm_[b]) w = Warm{};
}

void ContactImpulses::forgetAll() {
  for (size_t b = 0; b < warm_.size(); ++b) forget(static_cast<int>(b));
}

void ContactImpulses::placeCorners(int b, const Body& body) {
  // Only the corners on the surface can touch first; the others are never looked at.
  const BodySurface& surface = *surfaces_[b];
  const Eigen::VectorXd& x = body.positions();
  std::vector<Eigen::Vector3d>& corners = corners_[b];
  for (int c : surface.nodes()) {
    const SurfacePoint point = surface.corner(c);
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (int k = 0; k < point.count; ++k) p += point.weights[k] * x.segment<3>(3 * point.nodes[k]);
    corners[c] = p;
  }
}

void ContactImpulses::resolve(BodyList& bodies, const std::vector<PlacedShape>& obstacles,
                              const std::vector<Eigen::Isometry3d>& start_poses, double dt,
                              std::vector<StepReport>& reports) {
  touches_.clear();
  const int n = static_cast<int>(bodies.size());
  for (int b = 0; b < n; ++b) {
    body_start_[b] = static_cast<int>(touches_.size());
    loads_[b].assign(obstacles.size(), ContactLoad{});  // allocates only when their number grows
    if (!surfaces_[b]) continue;
    placeCorners(b, bodies[b]);
    findObstacleTouches(b, surfaces_[b]->nodes(), corners_[b], obstacles, start_poses, dt,
                        margins_[b], touches_);
  }
  body_start_[n] = static_cast<int>(touches_.size());
  const int count = body_start_[n];
  last_solve_ = ContactSolveReport{};
  if (count == 0) {
    for (int b = 0; b < n; ++b) forget(b);
    return;
  }
  if (static_cast<int>(kept_.capacity()) < count) kept_.reserve(2 * count);
  kept_.resize(count);
  for (int b = 0; b < n; ++b) {
    if (body_start_[b + 1] > body_start_[b]) participants_[b]->begin(dt);
  }
  // Every corner's nodes first, then their sums: a sum kept before a later corner added its
  // nodes would not cover them.
  for (int pass = 0; pass < 2; ++pass) {
    for (int i = 0; i < count; ++i) {
      const ObstacleTouch& t = touches_[i];
      kept_[i] = participants_[t.body]->keepCorner(t.corner, surfaces_[t.body]->corner(t.corner));
    }
  }
  problem_.begin(count);
  for (int i = 0; i < count; ++i) setContact(i, dt);
  addCouplings();
  last_solve_ = problem_.solve(solve_settings_);
  apply(bodies, obstacles, dt, reports);
}

void ContactImpulses::setContact(int i, double dt) {
  const ObstacleTouch& t = touches_[i];
  ContactParticipant& body = *participants_[t.body];
  const SurfacePoint point = surfaces_[t.body]->corner(t.corner);
  const Eigen::Matrix3d frame = contactFrameFor(t.normal);
  const Eigen::Vector3d relative = body.velocity(point) - t.obstacle_velocity;
  // The gap at the step's start, had the point and the obstacle moved at these velocities.
  const double start_gap = t.gap - dt * relative.dot(t.normal);
  const double target =
      start_gap >= 0.0 ? -start_gap / dt : std::min(-start_gap / dt, kPushOutSpeed);
  problem_.setContact(i, frame, settings_.friction, frame.transpose() * relative, target);
  problem_.addDiagonal(i, problem_.inContactFrames(i, i, body.compliance(point, false, kept_[i])));
  const Warm& warm = warm_[t.body][t.corner];
  if (warm.obstacle == t.obstacle) problem_.setImpulse(i, frame.transpose() * warm.impulse);
}

void ContactImpulses::addCouplings() {
  for (size_t b = 0; b + 1 < body_start_.size(); ++b) {
    const int first = body_start_[b], end = body_start_[b + 1];
    for (int i = first; i < end; ++i) {
      const SurfacePoint at = surfaces_[b]->corner(touches_[i].corner);
      for (int j = i + 1; j < end; ++j) {
        const SurfacePoint from = surfaces_[b]->corner(touches_[j].corner);
        const Eigen::Matrix3d w = participants_[b]->coupling(at, from, kept_[j]);
        problem_.addCoupling(i, j, problem_.inContactFrames(i, j, w));
      }
    }
  }
}

void ContactImpulses::apply(BodyList& bodies, const std::vector<PlacedShape>& obstacles, double dt,
                            std::vector<StepReport>& reports) {
  const int n = static_cast<int>(bodies.size());
  for (int b = 0; b < n; ++b) {
    const int first = body_start_[b], end = body_start_[b + 1];
    if (first == end) {
      forget(b);
      continue;
    }
    for (Warm& w : warm_[b]) w.obstacle = -1;
    for (int i = first; i < end; ++i) {
      const ObstacleTouch& t = touches_[i];
      const Eigen::Vector3d impulse = problem_.worldImpulse(i);
      participants_[b]->push(surfaces_[b]->corner(t.corner), impulse, false, kept_[i]);
      ContactLoad& load = loads_[b][t.obstacle];
      load.penetration = std::max(load.penetration, -t.gap);
      if (!(problem_.impulse(i)[0] > 0.0)) continue;
      warm_[b][t.corner] = Warm{t.obstacle, impulse};
      const Eigen::Vector3d force = impulse / dt;
      load.force += force;
      load.torque += t.position.cross(force);
      load.centre += t.position;
      ++load.points;
    }
    participants_[b]->end();
    placeCorners(b, bodies[b]);
    int touching = 0;
    for (int i = first; i < end; ++i) {
      const ObstacleTouch& t = touches_[i];
      ContactLoad& load = loads_[b][t.obstacle];
      const PlacedShape& obstacle = obstacles[t.obstacle];
      const double gap =
          signedDistance(obstacle.shape, obstacle.pose.inverse() * corners_[b][t.corner]);
      if (problem_.impulse(i)[0] > 0.0) load.depth = std::max(load.depth, -gap);
    }
    for (ContactLoad& load : loads_[b]) {
      if (load.points > 0) load.centre /= load.points;
      touching += load.points;
    }
    reports[b].contacts += touching;
  }
}

}  // namespace deformable_sim::core
