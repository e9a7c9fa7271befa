#include "deformable_sim/core/contact/contact_impulses.h"

#include <algorithm>
#include <cmath>

namespace deformable_sim::core {

ContactImpulses::ContactImpulses(BodyList& bodies, const ContactSettings& settings,
                                 const std::vector<bool>& takes_part)
    : settings_(settings),
      surfaces_(bodies.size()),
      participants_(bodies.size()),
      starts_(bodies.size()),
      velocities_(bodies.size()),
      margins_(bodies.size(), 0.0),
      body_start_(bodies.size() + 1, 0),
      loads_(bodies.size()),
      warm_(bodies.size()) {
  for (size_t b = 0; b < bodies.size(); ++b) {
    if (!takes_part[b]) continue;
    Body& body = bodies[b];
    surfaces_[b].emplace(body.mesh(), body.positions(), false);
    participants_[b] = body.contactParticipant();
    starts_[b].resize(body.numNodes());
    velocities_[b].resize(body.numNodes());
    margins_[b] = kMarginOfSize * surfaces_[b]->size();
    warm_[b].resize(body.numNodes() + surfaces_[b]->triangles().size());
  }
}

void ContactImpulses::embed(int b, const EmbeddedSurface& surface, const Body& body) {
  if (!surfaces_[b]) return;
  surfaces_[b].emplace(surface, body.positions());
  margins_[b] = kMarginOfSize * surfaces_[b]->size();
  const size_t corners = surface.numVertices();
  starts_[b].resize(corners);
  velocities_[b].resize(corners);
  warm_[b].assign(corners + surface.triangles().size(), Warm{});
}

void ContactImpulses::forget(int b) {
  for (Warm& w : warm_[b]) w = Warm{};
}

void ContactImpulses::forgetAll() {
  for (size_t b = 0; b < warm_.size(); ++b) forget(static_cast<int>(b));
}

void ContactImpulses::placeCorners(int b, const FiniteElementBody& body) {
  // Only the corners on the surface can touch first; the others are never looked at.
  const BodySurface& surface = *surfaces_[b];
  const Eigen::VectorXd &x = body.stepStart(), &v = body.velocities();
  for (int c : surface.nodes()) {
    const SurfacePoint point = surface.corner(c);
    Eigen::Vector3d start = Eigen::Vector3d::Zero(), velocity = Eigen::Vector3d::Zero();
    for (int k = 0; k < point.count; ++k) {
      start += point.weights[k] * x.segment<3>(3 * point.nodes[k]);
      velocity += point.weights[k] * v.segment<3>(3 * point.nodes[k]);
    }
    starts_[b][c] = start;
    velocities_[b][c] = velocity;
  }
}

SurfacePoint ContactImpulses::pointOf(const ObstacleTouch& touch) const {
  const BodySurface& surface = *surfaces_[touch.body];
  if (touch.face < 0) return surface.corner(touch.corner);
  return surface.trianglePoint(surface.triangles()[touch.face], touch.weights);
}

int ContactImpulses::warmSlot(const ObstacleTouch& touch) const {
  if (touch.face < 0) return touch.corner;
  return static_cast<int>(starts_[touch.body].size()) + touch.face;
}

int ContactImpulses::keepPoint(const ObstacleTouch& touch, bool with_sums) {
  ContactParticipant& body = *participants_[touch.body];
  const BodySurface& surface = *surfaces_[touch.body];
  if (touch.face < 0) return body.keepCorner(touch.corner, surface.corner(touch.corner));
  const Triangle& face = surface.triangles()[touch.face];
  std::array<int, 3> kept{};
  for (int k = 0; k < 3; ++k) kept[k] = body.keepCorner(face[k], surface.corner(face[k]));
  if (!with_sums || *std::min_element(kept.begin(), kept.end()) < 0) return -1;
  return body.keepSum(kept.data(), touch.weights.data(), 3);
}

Eigen::Vector3d ContactImpulses::freeStep(const SurfacePoint& point, const FiniteElementBody& body,
                                          double dt) {
  Eigen::Vector3d step = Eigen::Vector3d::Zero();
  for (int k = 0; k < point.count; ++k) {
    step += point.weights[k] * dt * body.velocities().segment<3>(3 * point.nodes[k]);
  }
  return step;
}

Eigen::Vector3d ContactImpulses::pointNow(const ObstacleTouch& touch, const Body& body) const {
  const SurfacePoint point = pointOf(touch);
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int k = 0; k < point.count; ++k) {
    p += point.weights[k] * body.positions().segment<3>(3 * point.nodes[k]);
  }
  return p;
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
    placeCorners(b, *bodies[b].finiteElements());
    findObstacleTouches(b, surfaces_[b]->nodes(), starts_[b], velocities_[b], obstacles,
                        start_poses, dt, margins_[b], touches_);
    findFaceTouches(b, *surfaces_[b], starts_[b], velocities_[b], obstacles, start_poses, dt,
                    margins_[b], near_triangles_, touches_);
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
    for (int i = 0; i < count; ++i) kept_[i] = keepPoint(touches_[i], pass == 1);
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
  const SurfacePoint point = pointOf(t);
  const Eigen::Matrix3d frame = contactFrameFor(t.normal);
  const Eigen::Vector3d relative = body.velocity(point) - t.obstacle_velocity;
  const double target = t.gap >= 0.0 ? -t.gap / dt : std::min(-t.gap / dt, kPushOutSpeed);
  problem_.setContact(i, frame, settings_.friction, frame.transpose() * relative, target);
  problem_.addDiagonal(i, problem_.inContactFrames(i, i, body.compliance(point, false, kept_[i])));
  const Warm& warm = warm_[t.body][warmSlot(t)];
  if (warm.obstacle == t.obstacle) problem_.setImpulse(i, frame.transpose() * warm.impulse);
}

void ContactImpulses::addCouplings() {
  for (size_t b = 0; b + 1 < body_start_.size(); ++b) {
    const int first = body_start_[b], end = body_start_[b + 1];
    for (int i = first; i < end; ++i) {
      const SurfacePoint at = pointOf(touches_[i]);
      for (int j = i + 1; j < end; ++j) {
        const SurfacePoint from = pointOf(touches_[j]);
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
      const SurfacePoint point = pointOf(t);
      // How deep the free step took it past the face it was outside of (not to the nearest face:
      // a point that crossed a thin table in the step is deep in it, not near its underside).
      const Eigen::Vector3d relative =
          freeStep(point, *bodies[b].finiteElements(), dt) - dt * t.obstacle_velocity;
      ContactLoad& load = loads_[b][t.obstacle];
      load.penetration = std::max(load.penetration, -(t.gap + t.normal.dot(relative)));
      participants_[b]->push(point, problem_.worldImpulse(i), false, kept_[i]);
    }
    participants_[b]->end();
    addLoads(b, bodies[b], obstacles, dt);
    for (const ContactLoad& load : loads_[b]) reports[b].contacts += load.points;
  }
}

void ContactImpulses::addLoads(int b, const Body& body, const std::vector<PlacedShape>& obstacles,
                               double dt) {
  for (int i = body_start_[b]; i < body_start_[b + 1]; ++i) {
    if (!(problem_.impulse(i)[0] > 0.0)) continue;
    const ObstacleTouch& t = touches_[i];
    const Eigen::Vector3d impulse = problem_.worldImpulse(i);
    const PlacedShape& obstacle = obstacles[t.obstacle];
    // A point on two shapes of one name (a link's two collision boxes) is one of its points.
    Warm& warm = warm_[b][warmSlot(t)];
    const bool counted = warm.obstacle >= 0 && obstacles[warm.obstacle].name == obstacle.name;
    warm = Warm{t.obstacle, impulse};
    const Eigen::Vector3d at = pointNow(t, body), force = impulse / dt;
    ContactLoad& load = loads_[b][t.obstacle];
    load.force += force;
    load.torque += at.cross(force);
    if (!counted) {
      load.centre += at;
      ++load.points;
    }
    load.depth =
        std::max(load.depth, -signedDistance(obstacle.shape, obstacle.pose.inverse() * at));
  }
  for (ContactLoad& load : loads_[b]) {
    if (load.points > 0) load.centre /= load.points;
  }
}

}  // namespace deformable_sim::core
