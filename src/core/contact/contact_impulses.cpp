#include "deformable_sim/core/contact/contact_impulses.h"

#include <algorithm>
#include <cmath>

#include "deformable_sim/core/base/wall_clock.h"

namespace deformable_sim::core {

ContactImpulses::ContactImpulses(BodyList& bodies, const ContactSettings& settings,
                                 const std::vector<bool>& takes_part, BodyContact* between)
    : settings_(settings),
      surfaces_(bodies.size()),
      between_(between),
      participants_(bodies.size(), nullptr),
      owned_(bodies.size()),
      begun_(bodies.size(), 0),
      starts_(bodies.size()),
      velocities_(bodies.size()),
      margins_(bodies.size(), 0.0),
      body_start_(bodies.size() + 1, 0),
      loads_(bodies.size()),
      warm_(bodies.size()),
      on_body_(bodies.size()) {
  for (size_t b = 0; b < bodies.size(); ++b) {
    Body& body = bodies[b];
    participants_[b] = between_ ? between_->participant(static_cast<int>(b)) : nullptr;
    if (!takes_part[b]) continue;
    surfaces_[b].emplace(body.mesh(), body.positions(), false);
    if (!participants_[b]) {
      owned_[b] = body.contactParticipant();
      participants_[b] = owned_[b].get();
    }
    starts_[b].resize(body.numNodes());
    velocities_[b].resize(body.numNodes());
    margins_[b] = kMarginOfSize * surfaces_[b]->size();
    warm_[b].resize(body.numNodes() + surfaces_[b]->triangles().size());
  }
  reserveProblem();
}

void ContactImpulses::reserveProblem() {
  // A contact per corner and per triangle touching an obstacle, and per corner and edge hit
  // between bodies; couplings as for a few dozen neighbours each (more grow the storage once).
  int contacts = 0;
  for (size_t b = 0; b < surfaces_.size(); ++b) {
    if (surfaces_[b]) contacts += surfaces_[b]->nodes().size() + surfaces_[b]->triangles().size();
    if (!between_ || !between_->takesPart(static_cast<int>(b))) continue;
    const BodySurface& surface = between_->surface(static_cast<int>(b));
    contacts += surface.nodes().size() + BodyContact::kEdgeHits * surface.edges().size();
  }
  problem_.reserve(contacts, kCouplingsPerContact * contacts);
  touches_.reserve(contacts);
  sides_.reserve(contacts);
}

void ContactImpulses::embed(int b, const EmbeddedSurface& surface, const Body& body) {
  if (!surfaces_[b]) return;
  surfaces_[b].emplace(surface, body.positions());
  margins_[b] = kMarginOfSize * surfaces_[b]->size();
  const size_t corners = surface.numVertices();
  starts_[b].resize(corners);
  velocities_[b].resize(corners);
  warm_[b].assign(corners + surface.triangles().size(), Warm{});
  reserveProblem();
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
    starts_[b][c] = point.of(x);
    velocities_[b][c] = point.of(v);
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

SurfaceCorners ContactImpulses::cornersOf(const ObstacleTouch& touch) const {
  if (touch.face < 0) return {1, {touch.corner, 0, 0}, {1.0, 0.0, 0.0}};
  const Triangle& face = surfaces_[touch.body]->triangles()[touch.face];
  return {3, {face[0], face[1], face[2]}, touch.weights};
}

int ContactImpulses::keepSide(const Side& side, bool with_sums) {
  ContactParticipant& body = *participants_[side.body];
  const BodySurface& surface = surfaceOf(side.body);
  const SurfaceCorners& corners = side.corners;
  std::array<int, 3> kept{};
  for (int k = 0; k < corners.count; ++k) {
    kept[k] = body.keepCorner(corners.ids[k], surface.corner(corners.ids[k]));
  }
  if (corners.count == 1 && corners.weights[0] == 1.0) return kept[0];
  if (!with_sums || *std::min_element(kept.begin(), kept.begin() + corners.count) < 0) return -1;
  return body.keepSum(kept.data(), corners.weights.data(), corners.count);
}

Eigen::Vector3d ContactImpulses::freeStep(const SurfacePoint& point, const FiniteElementBody& body,
                                          double dt) {
  return dt * point.of(body.velocities());
}

Eigen::Vector3d ContactImpulses::pointNow(const ObstacleTouch& touch, const Body& body) const {
  return pointOf(touch).of(body.positions());
}

void ContactImpulses::resolve(BodyList& bodies, const std::vector<PlacedShape>& obstacles,
                              const std::vector<Eigen::Isometry3d>& start_poses, double dt,
                              int threads, std::vector<StepReport>& reports) {
  const int count = findContacts(bodies, obstacles, start_poses, dt, threads, reports);
  last_solve_ = ContactSolveReport{};
  // Every corner's nodes first, then their sums: a sum kept before a later corner added its
  // nodes would not cover them.
  for (int pass = 0; pass < 2; ++pass) {
    for (std::array<Side, 2>& sides : sides_) {
      for (Side& side : sides) {
        if (side.body >= 0 && side.moves) side.kept = keepSide(side, pass == 1);
      }
    }
  }
  problem_.begin(count);
  for (int i = 0; i < count; ++i) setContact(i, dt);
  addCouplings();
  if (count > 0) last_solve_ = problem_.solve(solve_settings_);
  apply(bodies, obstacles, dt, reports);
}

int ContactImpulses::findContacts(BodyList& bodies, const std::vector<PlacedShape>& obstacles,
                                  const std::vector<Eigen::Isometry3d>& start_poses, double dt,
                                  int threads, std::vector<StepReport>& reports) {
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
  // Contact between bodies begins its participants; the others begin here, where they touch.
  time_between_ = 0.0;
  if (between_) {
    const WallClock::time_point start = WallClock::now();
    between_->find(bodies, dt, threads, reports);
    time_between_ += secondsSince(start);
  }
  for (int b = 0; b < n; ++b) {
    begun_[b] = owned_[b] && body_start_[b + 1] > body_start_[b];
    if (begun_[b]) participants_[b]->begin(dt);
  }
  const int between = between_ ? static_cast<int>(between_->contacts().size()) : 0;
  sides_.resize(touches_.size() + between);
  for (size_t i = 0; i < touches_.size(); ++i) {
    const ObstacleTouch& t = touches_[i];
    const SurfacePoint point = pointOf(t);
    // A point mostly on held nodes is the holds' to keep out (see BodyContact::kMovable).
    const bool moves = participants_[t.body]->movable(point) >= BodyContact::kMovable;
    sides_[i] = {Side{t.body, point, cornersOf(t), 1.0, moves}, Side{}};
  }
  for (int j = 0; j < between; ++j) {
    const BodyContact::Contact& c = between_->contacts()[j];
    sides_[touches_.size() + j] = {
        Side{c.node_body, c.node, c.node_corners, 1.0, c.node_moves},
        Side{c.triangle_body, c.triangle, c.triangle_corners, -1.0, c.triangle_moves}};
  }
  return static_cast<int>(sides_.size());
}

void ContactImpulses::setContact(int i, double dt) {
  const int touches = static_cast<int>(touches_.size());
  Eigen::Vector3d normal, relative = Eigen::Vector3d::Zero(), warm = Eigen::Vector3d::Zero();
  double gap = 0.0;
  if (i < touches) {
    const ObstacleTouch& t = touches_[i];
    normal = t.normal;
    gap = t.gap;
    relative = -t.obstacle_velocity;
    const Warm& last = warm_[t.body][warmSlot(t)];
    if (last.obstacle == t.obstacle) warm = last.impulse;
  } else {
    const BodyContact::Contact& c = between_->contacts()[i - touches];
    normal = c.normal;
    gap = c.start_gap;
    warm = between_->lastImpulse(i - touches);
  }
  const std::array<Side, 2>& sides = sides_[i];
  Eigen::Matrix3d w = Eigen::Matrix3d::Zero();
  for (const Side& side : sides) {
    if (side.body < 0) continue;
    const ContactParticipant& body = *participants_[side.body];
    relative += side.sign * body.velocity(side.point);
    // As the body will answer (not symmetrized: see ContactProblem::addCoupling).
    if (side.moves) w += body.coupling(side.point, side.point, side.kept);
  }
  // A body touching itself: each side's impulse moves the other side too.
  if (sides[0].body == sides[1].body && sides[0].moves && sides[1].moves) {
    const ContactParticipant& body = *participants_[sides[0].body];
    w -= body.coupling(sides[0].point, sides[1].point, sides[1].kept) +
         body.coupling(sides[1].point, sides[0].point, sides[0].kept);
  }
  const Eigen::Matrix3d frame = contactFrameFor(normal);
  const double target = gap >= 0.0 ? -gap / dt : std::min(-gap / dt, kPushOutSpeed);
  problem_.setContact(i, frame, settings_.friction, frame.transpose() * relative, target);
  problem_.addDiagonal(i, problem_.inContactFrames(i, i, w));
  if (!warm.isZero(0.0)) problem_.setImpulse(i, frame.transpose() * warm);
}

Eigen::Vector3d ContactImpulses::velocityNow(int i, const BodyList& bodies) const {
  const int touches = static_cast<int>(touches_.size());
  Eigen::Vector3d v =
      i < touches ? Eigen::Vector3d(-touches_[i].obstacle_velocity) : Eigen::Vector3d::Zero();
  for (const Side& side : sides_[i]) {
    if (side.body >= 0) v += side.sign * side.point.of(bodies[side.body].velocities());
  }
  return problem_.frame(i).transpose() * v;
}

void ContactImpulses::addCouplings() {
  for (std::vector<std::pair<int, int>>& on : on_body_) on.clear();
  for (int i = 0; i < static_cast<int>(sides_.size()); ++i) {
    for (int k = 0; k < 2; ++k) {
      const Side& side = sides_[i][k];
      if (side.body >= 0 && side.moves) on_body_[side.body].emplace_back(i, k);
    }
  }
  for (size_t b = 0; b < on_body_.size(); ++b) {
    const std::vector<std::pair<int, int>>& on = on_body_[b];
    for (size_t x = 0; x < on.size(); ++x) {
      const Side& at = sides_[on[x].first][on[x].second];
      for (size_t y = x + 1; y < on.size(); ++y) {
        if (on[y].first == on[x].first) continue;  // one contact's two sides: its diagonal
        const Side& from = sides_[on[y].first][on[y].second];
        const ContactParticipant& body = *participants_[b];
        const double sign = at.sign * from.sign;
        const int i = on[x].first, j = on[y].first;
        problem_.addCoupling(
            i, j,
            problem_.inContactFrames(i, j, sign * body.coupling(at.point, from.point, from.kept)),
            problem_.inContactFrames(j, i, sign * body.coupling(from.point, at.point, at.kept)));
      }
    }
  }
}

void ContactImpulses::apply(BodyList& bodies, const std::vector<PlacedShape>& obstacles, double dt,
                            std::vector<StepReport>& reports) {
  const int n = static_cast<int>(bodies.size());
  for (int i = body_start_[0]; i < body_start_[n]; ++i) {
    const ObstacleTouch& t = touches_[i];
    // How deep the free step took it past the face it was outside of (not to the nearest face:
    // a point that crossed a thin table in the step is deep in it, not near its underside).
    const Eigen::Vector3d relative =
        freeStep(sides_[i][0].point, *bodies[t.body].finiteElements(), dt) -
        dt * t.obstacle_velocity;
    ContactLoad& load = loads_[t.body][t.obstacle];
    load.penetration = std::max(load.penetration, -(t.gap + t.normal.dot(relative)));
  }
  for (int i = 0; i < static_cast<int>(sides_.size()); ++i) {
    const Eigen::Vector3d impulse = problem_.worldImpulse(i);
    for (const Side& side : sides_[i]) {
      if (side.body >= 0 && side.moves) {
        participants_[side.body]->push(side.point, side.sign * impulse, false, side.kept);
      }
    }
  }
  for (int b = 0; b < n; ++b) {
    if (begun_[b] || (between_ && between_->takesPart(b))) participants_[b]->end();
  }
  for (int b = 0; b < n; ++b) {
    if (body_start_[b + 1] == body_start_[b]) {
      forget(b);
      continue;
    }
    for (Warm& w : warm_[b]) w.obstacle = -1;
    addLoads(b, bodies[b], obstacles, dt);
    for (const ContactLoad& load : loads_[b]) reports[b].contacts += load.points;
  }
  const int touches = static_cast<int>(touches_.size());
  if (!between_) return;
  for (int j = 0; j + touches < static_cast<int>(sides_.size()); ++j) {
    between_->takeImpulse(j, problem_.worldImpulse(touches + j));
  }
  const WallClock::time_point start = WallClock::now();
  between_->finishStep(bodies, dt, reports);
  time_between_ += secondsSince(start);
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
