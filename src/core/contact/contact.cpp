#include "deformable_sim/core/contact/contact.h"

#include <algorithm>
#include <tuple>
#include <utility>

namespace deformable_sim::core {

namespace {

/// Halvings of a point's way in the step that find where it entered an obstacle: 2^-40 of it.
constexpr int kEntryHalvings = 40;

/// The body's mass and the velocity of its centre of mass.
std::pair<double, Eigen::Vector3d> massAndCentreVelocity(const FiniteElementBody& body) {
  double mass = 0.0;
  Eigen::Vector3d momentum = Eigen::Vector3d::Zero();
  for (int i = 0; i < body.numNodes(); ++i) {
    mass += body.nodalMasses()[i];
    momentum += body.nodalMasses()[i] * body.velocities().segment<3>(3 * i);
  }
  return {mass, momentum / mass};
}

}  // namespace

ContactState::ContactState(const Mesh& mesh)
    : points_(mesh.numNodes()),
      node_obstacle_(mesh.numNodes(), -1),
      node_place_(mesh.numNodes(), Eigen::Vector3d::Zero()),
      held_flag_(mesh.numNodes(), 0),
      held_weight_(mesh.numNodes(), 0.0),
      on_plane_node_(mesh.numNodes(), 0),
      plane_weight_(mesh.numNodes(), 0.0),
      position_requests_(mesh.numNodes()),
      velocity_requests_(mesh.numNodes()) {
  const int num_nodes = mesh.numNodes();
  for (int i = 0; i < num_nodes; ++i) {
    points_[i].nodes[0] = i;
    points_[i].weights[0] = 1.0;
    points_[i].count = 1;
  }
  for (const Face& f : extractBoundary(mesh)) {
    faces_.emplace_back(f.nodes[0], f.nodes[1], f.nodes[2]);
    if (f.size() == 4) faces_.emplace_back(f.nodes[0], f.nodes[2], f.nodes[3]);
  }
  face_obstacle_.assign(num_nodes, -1);
  face_normal_.assign(num_nodes, Eigen::Vector3d::Zero());
  face_place_.assign(num_nodes, Eigen::Vector3d::Zero());
  pushed_by_.assign(num_nodes, -1);
  face_push_.assign(num_nodes, 0.0);
  face_sticks_.assign(num_nodes, 0);
  face_held_in_place_.assign(num_nodes, 0);
  face_friction_.assign(num_nodes, Eigen::Vector3d::Zero());
  face_excess_.assign(num_nodes, Eigen::Vector3d::Zero());
  face_nodes_.reserve(num_nodes);
  face_held_.reserve(num_nodes);
  held_.reserve(num_nodes);
  plane_nodes_.reserve(num_nodes);
  resizePoints();
}

void ContactState::embed(const EmbeddedSurface& surface) {
  points_.assign(surface.numVertices(), Point{});
  for (int v = 0; v < surface.numVertices(); ++v) {
    const SurfacePoint vertex = vertexPoint(surface, v);
    Point& point = points_[v];
    point.count = vertex.count;
    std::copy_n(vertex.nodes.begin(), vertex.count, point.nodes.begin());
    std::copy_n(vertex.weights.begin(), vertex.count, point.weights.begin());
  }
  faces_ = surface.triangles();
  embedded_ = true;
  resizePoints();
}

void ContactState::resizePoints() {
  const size_t n = points_.size();
  obstacle_.assign(n, -1);
  point_.assign(n, Eigen::Vector3d::Zero());
  normal_.assign(n, Eigen::Vector3d::Zero());
  holds_.assign(n, 0);
  slip_.assign(n, Eigen::Vector3d::Zero());
  point_held_.assign(n, 0);
  on_plane_.assign(n, 0);
  friction_.assign(n, Eigen::Vector3d::Zero());
  excess_.assign(n, Eigen::Vector3d::Zero());
  point_force_.assign(n, Eigen::Vector3d::Zero());
  face_pressed_.assign(faces_.size(), 0);
  point_x_.assign(n, Eigen::Vector3d::Zero());
  face_touches_.clear();
  face_touches_.reserve(faces_.size());
}

void ContactState::forget() {
  std::fill(obstacle_.begin(), obstacle_.end(), -1);
  std::fill(holds_.begin(), holds_.end(), 0);
  std::fill(on_plane_.begin(), on_plane_.end(), 0);
  // Between steps: no face node is held now (letGo() released them).
  for (int i : face_nodes_) {
    face_obstacle_[i] = -1, face_sticks_[i] = 0;
    face_friction_[i].setZero(), face_excess_[i].setZero();
  }
  face_nodes_.clear();
  for (int i : face_held_) pushed_by_[i] = -1;
  face_held_.clear();
  face_touches_.clear();
}

void ContactState::resizeForObstacles(size_t count) {
  if (contacts_.size() != count) {  // allocates only when the scene's obstacles change
    contacts_.resize(count);
    patches_.resize(count);
    to_shape_.resize(count);
  }
  std::fill(contacts_.begin(), contacts_.end(), ContactLoad{});
  std::fill(patches_.begin(), patches_.end(), Patch{});
}

Eigen::Vector3d ContactState::worldNormal(const std::vector<PlacedShape>& obstacles, int p) const {
  return obstacles[obstacle_[p]].pose.linear() * normal_[p];
}

void ContactState::addForce(int k, const Eigen::Vector3d& at, const Eigen::Vector3d& force) {
  contacts_[k].force += force;
  contacts_[k].torque += at.cross(force);
}

Eigen::Vector3d ContactState::weighted(const Eigen::VectorXd& state, int p) const {
  const Point& point = points_[p];
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int k = 0; k < point.count; ++k)
    sum += point.weights[k] * state.segment<3>(3 * point.nodes[k]);
  return sum;
}

double ContactState::freeWeight(const FiniteElementBody& body, int p) const {
  const Point& point = points_[p];
  double free = 0.0;
  for (int k = 0; k < point.count; ++k) {
    if (!body.isConstrained(point.nodes[k])) free += point.weights[k];
  }
  return free;
}

bool ContactState::movable(const FiniteElementBody& body, int p) const {
  const Point& point = points_[p];
  if (point.count == 1) return !body.isConstrained(point.nodes[0]);
  return freeWeight(body, p) >= kMovable;
}

ContactState::Requests::Requests(int num_nodes)
    : weight(num_nodes, 0.0), sum(num_nodes, Eigen::Vector3d::Zero()) {
  touched.reserve(num_nodes);
}

void ContactState::request(const FiniteElementBody& body, int p, const Eigen::Vector3d& change,
                           Requests& requests) const {
  // Moving a vertex's free nodes all alike by change / (their weight) moves it by `change`, its
  // cell shifted, not strained (moving each node by its weight, the least change of the nodes
  // that does it, strained the cells under a resting tube by a tenth, and held so, they pushed
  // it off the floor).
  const Point& point = points_[p];
  const Eigen::Vector3d shift = change / freeWeight(body, p);
  for (int k = 0; k < point.count; ++k) {
    const int i = point.nodes[k];
    if (body.isConstrained(i)) continue;
    if (requests.weight[i] == 0.0) requests.touched.push_back(i);
    requests.weight[i] += point.weights[k];
    requests.sum[i] += point.weights[k] * shift;
  }
}

void ContactState::grant(Requests& requests, Eigen::VectorXd& state) const {
  // Each node by the mean of what its vertices ask, weighted as they lie on it: vertices that
  // share nodes and ask alike (a flat face on a floor) get exactly that, whatever their order
  // (one after another, each shifting shared nodes again, they left the shipped sponge's bottom
  // 0.24 mm above the floor and lifted a vertex of its side by 1.2 mm).
  for (int i : requests.touched) {
    state.segment<3>(3 * i) += requests.sum[i] / requests.weight[i];
    requests.weight[i] = 0.0;
    requests.sum[i].setZero();
  }
  requests.touched.clear();
}

void ContactState::hold(FiniteElementBody& body, const std::vector<PlacedShape>& obstacles,
                        double dt) {
  whole_ = takenWhole(body);
  held_.clear();
  for (size_t p = 0; p < points_.size(); ++p) {
    point_held_[p] = 0;
    const int k = obstacle_[p];
    if (k < 0 || !holds_[p]) continue;
    const Point& point = points_[p];
    if (on_plane_[p] && slidesOnPlanes()) {
      holdOnPlane(body, obstacles, static_cast<int>(p));
      continue;
    }
    on_plane_[p] = 0;
    // A sliding point is held where its slip takes it along the obstacle in the step: the
    // obstacle carries the body's weight through the solve whether it slides or not.
    const Eigen::Vector3d slide =
        whole_ ? Eigen::Vector3d(obstacles[k].pose.linear().transpose() * slip_[p] * dt)
               : Eigen::Vector3d::Zero();
    for (int j = 0; j < point.count; ++j) {
      const int i = point.nodes[j];
      if (node_obstacle_[i] != k) continue;  // its place was taken on another obstacle
      if (held_flag_[i]) {                   // by a neighbouring vertex in the same cell
        held_weight_[i] += point.weights[j];
        point_held_[p] = kInPlace;
        continue;
      }
      if (body.isConstrained(i) || on_plane_node_[i]) continue;  // held, or on a sliding plane
      body.holdNodeAt(i, obstacles[k].pose * (node_place_[i] + slide));
      held_.push_back(i);
      held_flag_[i] = 1;
      held_weight_[i] = point.weights[j];
      point_held_[p] = kInPlace;
    }
  }
  holdFaceNodes(body, obstacles);
}

bool ContactState::takenWhole(const FiniteElementBody& body) const {
  // Its change is along the face it touches: on several faces (wrapped round a plate pressed
  // into it, hanging on an edge) its points slide on their own planes instead.
  if (!face_nodes_.empty() || numConstrained(body) > 0) return false;
  int first = -1;
  for (size_t p = 0; p < points_.size(); ++p) {
    if (obstacle_[p] < 0) continue;  // held or not: what touches pushes on the body too
    if (first < 0) {
      first = static_cast<int>(p);
      continue;
    }
    if (obstacle_[p] != obstacle_[first] || normal_[p].dot(normal_[first]) < kOneFace) return false;
  }
  return true;
}

void ContactState::holdOnPlane(FiniteElementBody& body, const std::vector<PlacedShape>& obstacles,
                               int p) {
  // Each of its free nodes on a plane through its own place, with the point's normal; the
  // point's forces spread by its weights. A node several points share is held once.
  const int k = obstacle_[p];
  const Point& point = points_[p];
  const Eigen::Vector3d n = worldNormal(obstacles, p);
  for (int j = 0; j < point.count; ++j) {
    const int i = point.nodes[j];
    if (node_obstacle_[i] != k || body.isConstrained(i)) continue;
    if (!on_plane_node_[i]) {
      body.holdNodeOnPlane(i, n, obstacles[k].pose * node_place_[i]);
      on_plane_node_[i] = 1;
      plane_weight_[i] = 0.0;
      plane_nodes_.push_back(i);
    }
    plane_weight_[i] += point.weights[j];
    body.addStepForce(i, point.weights[j] * (friction_[p] - excess_[p]));
    point_held_[p] = kOnItsPlane;
  }
}

void ContactState::judgePatches(const FiniteElementBody& body,
                                const std::vector<PlacedShape>& obstacles,
                                const ContactSettings& settings, double dt) {
  // Coulomb's law for the held points on one obstacle together: single points carry uneven parts
  // of the load, and judging each by itself lets some slip while the body sticks (it creeps) and
  // keeps others held while it slides (it stops).
  const Eigen::VectorXd& reactions = body.reactionForces();
  for (size_t p = 0; p < points_.size(); ++p) {
    if (point_held_[p] != kInPlace) continue;
    // Its share of the forces on the nodes it holds, by its weight among the points holding them.
    const Point& point = points_[p];
    Eigen::Vector3d& r = point_force_[p];
    r.setZero();
    double mass = 0.0;
    for (int j = 0; j < point.count; ++j) {
      const int i = point.nodes[j];
      if (!held_flag_[i] || node_obstacle_[i] != obstacle_[p]) continue;
      const double part = point.weights[j] / held_weight_[i];
      r += part * reactions.segment<3>(3 * i);
      mass += part * body.nodalMasses()[i];
    }
    Patch& patch = patches_[obstacle_[p]];
    if (!patch.add(r, worldNormal(obstacles, static_cast<int>(p)), mass)) continue;
    if (whole_) patch.momentum += mass * slip_[p];  // otherwise it was held where it was
  }
  addFaceNodesToPatches(body, obstacles);
  decideSlides(body, settings, dt);
}

void ContactState::decideSlides(const FiniteElementBody& body, const ContactSettings& settings,
                                double dt) {
  // Sliding, an obstacle resists with μ times the push, against the slip (or, starting, the
  // tangential force it would have taken to hold it). What it resisted beyond that in the solve
  // goes back to the body: to a body on one face of one obstacle, held by nothing else, as a
  // whole, the patch sliding on with it (kicked alone, a patch's few nodes had the body stick and
  // slip in turn); to a body that touches several obstacles or faces or is held otherwise
  // (clamped, grasped), at the patch's own nodes, which slide on their planes: a kick of the
  // whole by each patch takes their forces on one another (a block squeezed between fingers
  // bulging against them) for a push, and threw a squeezed block off its table.
  // (A body taken whole touches one obstacle, hold() saw to it: one patch at most.)
  kick_.setZero();
  for (Patch& patch : patches_) {
    if (!(patch.mass > 0.0)) continue;
    const Eigen::Vector3d slip = patch.momentum / patch.mass;
    const double resisted = patch.sliding.norm(), friction = settings.friction * patch.pushing;
    if (slip.isZero(0.0) && resisted <= friction * (1.0 + 1e-12)) continue;  // it sticks
    patch.friction = slip.isZero(0.0) ? Eigen::Vector3d(friction / resisted * patch.sliding)
                                      : Eigen::Vector3d(-friction * slip.normalized());
    patch.slides = true;
    patch.sticks = false;
    if (!whole_) continue;  // its points slide on the obstacle's plane (release())
    const Eigen::Vector3d impulse = (patch.friction - patch.sliding) * dt;
    double mass;
    std::tie(mass, centre_velocity_) = massAndCentreVelocity(body);
    kick_ = impulse / mass;
    // Along the obstacle only: a kick into it sank the body into it. (Points' normals on the
    // face a body taken whole touches agree within kOneFace.)
    const Eigen::Vector3d n = patch.normal.normalized();
    kick_ -= kick_.dot(n) * n;
    // Friction that would turn its slip back stops it instead, within the step.
    if (!slip.isZero(0.0) && (slip + kick_).dot(slip) <= 0.0) {
      kick_ = -slip;
      patch.sticks = true;
    }
  }
}

void ContactState::release(FiniteElementBody& body, const std::vector<PlacedShape>& obstacles,
                           const std::vector<Eigen::Isometry3d>& start_poses,
                           const ContactSettings& settings, double dt) {
  resizeForObstacles(obstacles.size());
  judgePatches(body, obstacles, settings, dt);
  for (size_t p = 0; p < points_.size(); ++p) {
    // Points not held touch only if project() finds them inside again.
    if (!point_held_[p]) {
      obstacle_[p] = -1, holds_[p] = 0;
      continue;
    }
    if (point_held_[p] == kOnItsPlane) {
      judgeOnPlane(body, obstacles, start_poses, settings, dt, static_cast<int>(p));
      point_held_[p] = 0;
      continue;
    }
    const int k = obstacle_[p];
    const Patch& patch = patches_[k];
    const Eigen::Vector3d n = worldNormal(obstacles, static_cast<int>(p));
    const Eigen::Vector3d& r = point_force_[p];
    const double pushing = r.dot(n);
    point_held_[p] = 0;
    if (!(pushing > 0.0)) {  // it pulls: it lifts off
      obstacle_[p] = -1, holds_[p] = 0;
      continue;
    }
    const Eigen::Vector3d x = weighted(body.positions(), static_cast<int>(p));
    if (!patch.slides) {
      addForce(k, x, r);
      continue;
    }
    // Its share of the friction by its push; it slides on from where the step took it.
    addForce(k, x, pushing * n + pushing / patch.pushing * patch.friction);
    if (slidesOnPlanes()) {
      const double share = pushing / patch.pushing;
      slideOnPlane(static_cast<int>(p), share * patch.friction,
                   share * (patch.sliding - patch.friction));
      point_[p] = obstacles[k].pose.inverse() * x;
      continue;
    }
    // It slides on with the body's centre, not by what it was given alone: held along a slip of
    // its own, a corner the body tipped over dragged the body with it.
    const Eigen::Vector3d slip =
        centre_velocity_ + kick_ - weighted(body.velocities(), static_cast<int>(p)) + slip_[p];
    slip_[p] = patch.sticks ? Eigen::Vector3d::Zero() : Eigen::Vector3d(slip - slip.dot(n) * n);
    point_[p] = obstacles[k].pose.inverse() * x;
  }
  judgeFaceNodes(body, obstacles, start_poses, settings, dt);
  letGo(body);
}

void ContactState::letGo(FiniteElementBody& body) {
  for (int i : held_) {
    body.releaseNode(i);
    held_flag_[i] = 0;
  }
  held_.clear();
  for (int i : face_held_) {
    if (face_held_in_place_[i]) body.releaseNode(i);
    face_held_in_place_[i] = 0;
  }
  for (int i : plane_nodes_) on_plane_node_[i] = 0;
  plane_nodes_.clear();
  body.releasePlaneHolds();
  if (kick_.isZero(0.0)) return;
  Eigen::VectorXd& v = body.mutableVelocities();
  for (int i = 0; i < body.numNodes(); ++i) {
    if (!body.isConstrained(i)) v.segment<3>(3 * i) += kick_;
  }
}

void ContactState::slideOnPlane(int p, const Eigen::Vector3d& friction,
                                const Eigen::Vector3d& excess) {
  on_plane_[p] = 1;
  friction_[p] = friction;
  excess_[p] = excess;
  holds_[p] = 1;
}

void ContactState::judgeOnPlane(const FiniteElementBody& body,
                                const std::vector<PlacedShape>& obstacles,
                                const std::vector<Eigen::Isometry3d>& start_poses,
                                const ContactSettings& settings, double dt, int p) {
  const int k = obstacle_[p];
  const Point& point = points_[p];
  const Eigen::Vector3d n = worldNormal(obstacles, p);
  const Eigen::Vector3d x = weighted(body.positions(), p);
  double pushing = 0.0;  // its share of its nodes' springs, by its weight among their points
  for (int j = 0; j < point.count; ++j) {
    const int i = point.nodes[j];
    if (!on_plane_node_[i] || node_obstacle_[i] != k) continue;
    pushing += point.weights[j] / plane_weight_[i] * body.reactionForces().segment<3>(3 * i).dot(n);
  }
  const bool on_face =
      signedDistance(obstacles[k].shape, obstacles[k].pose.inverse() * x) < kOffItsFace;
  if (!(pushing > 0.0) || !on_face) {  // it lifts off, or slid past an edge
    obstacle_[p] = -1, holds_[p] = 0, on_plane_[p] = 0;
    return;
  }
  addForce(k, x, pushing * n + friction_[p] - excess_[p]);
  excess_[p].setZero();
  const Eigen::Vector3d slip =
      slipOn(obstacles[k], start_poses[k], x, weighted(body.velocities(), p), n, dt);
  point_[p] = obstacles[k].pose.inverse() * x;
  holds_[p] = 1;
  if (frictionStopped(friction_[p], slip)) {  // at rest: held where it is from now on
    on_plane_[p] = 0;
    slip_[p].setZero();
    return;
  }
  friction_[p] = -settings.friction * pushing * slip.normalized();
}

Eigen::Vector3d ContactState::obstacleVelocity(const PlacedShape& obstacle,
                                               const Eigen::Isometry3d& start_pose,
                                               const Eigen::Vector3d& x, double dt) {
  return (x - start_pose * (obstacle.pose.inverse() * x)) / dt;
}

Eigen::Vector3d ContactState::slipOn(const PlacedShape& obstacle,
                                     const Eigen::Isometry3d& start_pose, const Eigen::Vector3d& x,
                                     const Eigen::Vector3d& velocity, const Eigen::Vector3d& n,
                                     double dt) {
  const Eigen::Vector3d relative = velocity - obstacleVelocity(obstacle, start_pose, x, dt);
  return relative - relative.dot(n) * n;
}

bool ContactState::frictionStopped(const Eigen::Vector3d& friction, const Eigen::Vector3d& slip) {
  return friction.isZero(0.0) ? slip.norm() <= kAtRest : slip.dot(friction) >= 0.0;
}

Eigen::Vector3d ContactState::landingChange(const FiniteElementBody& body, int p,
                                            const Eigen::Vector3d& obstacle_velocity,
                                            const Eigen::Vector3d& normal,
                                            const ContactSettings& settings) {
  // It touches from here on, held in the next step and sliding at what it keeps along the
  // surface (the held step then takes friction from that, with the body behind it). Landing,
  // the impulse that stops it going in allows μ times itself of friction.
  const Eigen::Vector3d relative = weighted(body.velocities(), p) - obstacle_velocity;
  const double into = -relative.dot(normal);
  const Eigen::Vector3d along = relative + into * normal;
  if (!(into > 0.0)) {  // resting or leaving
    slip_[p] = whole_ ? along : Eigen::Vector3d::Zero();
    holds_[p] = whole_ || holds_[p] || along.isZero(0.0);
    if (slidesOnPlanes() && !along.isZero(0.0)) slideOnPlane(p, Eigen::Vector3d::Zero());
    return Eigen::Vector3d::Zero();
  }
  const double speed = along.norm(), slowed = settings.friction * into;
  slip_[p] =
      speed <= slowed ? Eigen::Vector3d::Zero() : Eigen::Vector3d(along * (1.0 - slowed / speed));
  // A body held otherwise slides on the obstacle's plane in the next solve.
  holds_[p] = whole_ || slip_[p].isZero(0.0);
  if (slidesOnPlanes() && !slip_[p].isZero(0.0)) slideOnPlane(p, Eigen::Vector3d::Zero());
  return into * normal + slip_[p] - along;
}

void ContactState::enterThroughItsFace(const Shape& shape, const Eigen::Isometry3d& to_start_shape,
                                       const Eigen::VectorXd& start, int p,
                                       const Eigen::Vector3d& now, Eigen::Vector3d& surface,
                                       Eigen::Vector3d& normal) const {
  // Where it was at the step's start, in the obstacle's frame then (it moves with the obstacle).
  // On its surface counts as outside: a node resting on a table was put there to round-off.
  Eigen::Vector3d outside = to_start_shape * weighted(start, p);
  // Moving into its nearest face, it came in through it (or beside it).
  if ((now - outside).dot(normal) <= 0.0) return;
  if (!(signedDistance(shape, outside) > -kOnTheSurface)) return;  // it was inside already
  Eigen::Vector3d inside = now;
  for (int k = 0; k < kEntryHalvings; ++k) {
    const Eigen::Vector3d middle = 0.5 * (outside + inside);
    (signedDistance(shape, middle) > -kOnTheSurface ? outside : inside) = middle;
  }
  Eigen::Vector3d entry, entry_normal;
  signedDistance(shape, inside, &entry, &entry_normal);
  // The nearest face is the one it came through, or beside it: it goes back there.
  if (entry_normal.dot(normal) > 0.0) return;
  surface = entry;
  normal = entry_normal;
}

void ContactState::settleEmbedded(FiniteElementBody& body, const PlacedShape& obstacle, int k) {
  const Eigen::Isometry3d to_shape = obstacle.pose.inverse();
  for (int pass = 0; pass < kEmbeddedPasses; ++pass) {
    for (size_t p = 0; p < points_.size(); ++p) {
      if (obstacle_[p] != k) continue;
      const int q = static_cast<int>(p);
      Eigen::Vector3d surface, normal;
      const Eigen::Vector3d x = weighted(body.positions(), q);
      if (signedDistance(obstacle.shape, to_shape * x, &surface, &normal) < 0.0) {
        request(body, q, obstacle.pose * surface - x, position_requests_);
      }
    }
    if (position_requests_.touched.empty()) return;
    grant(position_requests_, body.mutablePositions());
  }
}

void ContactState::grantVelocities(FiniteElementBody& body, int k, double dt) {
  // What the obstacle gave each node, as a force on the body.
  for (int i : velocity_requests_.touched) {
    const Eigen::Vector3d change = velocity_requests_.sum[i] / velocity_requests_.weight[i];
    addForce(k, body.positions().segment<3>(3 * i), body.nodalMasses()[i] * change / dt);
  }
  grant(velocity_requests_, body.mutableVelocities());
}

void ContactState::recordNodePlaces(const FiniteElementBody& body,
                                    const std::vector<PlacedShape>& obstacles) {
  for (size_t p = 0; p < points_.size(); ++p) {
    const int k = obstacle_[p];
    if (k < 0) continue;
    const Point& point = points_[p];
    if (point.count == 1) {  // a node: exactly its place on the surface
      node_obstacle_[point.nodes[0]] = k;
      node_place_[point.nodes[0]] = point_[p];
      continue;
    }
    const Eigen::Isometry3d to_shape = obstacles[k].pose.inverse();
    for (int j = 0; j < point.count; ++j) {
      const int i = point.nodes[j];
      node_obstacle_[i] = k;
      node_place_[i] = to_shape * body.positions().segment<3>(3 * i);
    }
  }
}

void ContactState::putBack(FiniteElementBody& body, int p, const Eigen::Vector3d& x,
                           const Eigen::Vector3d& on_surface, const Eigen::Vector3d& change,
                           double dt) {
  const int k = obstacle_[p];
  if (embedded_) {
    // The positions are granted together (project()); the velocities one vertex after another
    // (granted together too, the patch held under the shipped tube after its first step slid,
    // and it was kicked 12 cm aside).
    request(body, p, on_surface - x, position_requests_);
    if (change.isZero(0.0)) return;
    request(body, p, change, velocity_requests_);
    grantVelocities(body, k, dt);
    return;
  }
  const int i = points_[p].nodes[0];
  body.mutablePositions().segment<3>(3 * i) = on_surface;
  if (change.isZero(0.0)) return;
  body.mutableVelocities().segment<3>(3 * i) += change;
  addForce(k, on_surface, body.nodalMasses()[i] * change / dt);
}

int ContactState::countTouching(const FiniteElementBody& body,
                                const std::vector<PlacedShape>& obstacles) {
  for (size_t k = 0; k < obstacles.size(); ++k) to_shape_[k] = obstacles[k].pose.inverse();
  int touching = 0;
  for (ContactLoad& c : contacts_) c.points = 0, c.centre.setZero(), c.depth = 0.0;
  for (size_t p = 0; p < points_.size(); ++p) {
    if (obstacle_[p] < 0) continue;
    ++touching;
    ContactLoad& load = contacts_[obstacle_[p]];
    const Eigen::Vector3d x = weighted(body.positions(), static_cast<int>(p));
    ++load.points;
    load.centre += x;
    const PlacedShape& obstacle = obstacles[obstacle_[p]];
    const double inside = -signedDistance(obstacle.shape, to_shape_[obstacle_[p]] * x);
    load.depth = std::max(load.depth, inside);
  }
  for (const FaceTouch& touch : face_touches_) {
    ++touching;
    ContactLoad& load = contacts_[touch.obstacle];
    ++load.points;
    for (int corner = 0; corner < 3; ++corner)
      load.centre += point_x_[faces_[touch.face][corner]] / 3.0;
  }
  for (ContactLoad& c : contacts_) {
    if (c.points > 0) c.centre /= c.points;
  }
  return touching;
}

int ContactState::project(FiniteElementBody& body, const std::vector<PlacedShape>& obstacles,
                          const std::vector<Eigen::Isometry3d>& start_poses,
                          const ContactSettings& settings, double dt) {
  for (size_t k = 0; k < obstacles.size(); ++k) {
    const PlacedShape& obstacle = obstacles[k];
    const Eigen::Isometry3d to_shape = obstacle.pose.inverse();
    const Eigen::Isometry3d to_start = start_poses[k] * to_shape;  // the point a step ago
    for (size_t p = 0; p < points_.size(); ++p) {
      const int q = static_cast<int>(p);
      if (!movable(body, q)) continue;  // held: by the user or a grasp
      Eigen::Vector3d surface, normal;
      const Eigen::Vector3d x = weighted(body.positions(), q);
      if (!(signedDistance(obstacle.shape, to_shape * x, &surface, &normal) < 0.0)) continue;
      // A point held on this obstacle moved with it (to its place, or as far as it slid): it is
      // inside by round-off only, and touches on as it did.
      const bool stuck = obstacle_[p] == static_cast<int>(k) && holds_[p];
      if (obstacle_[p] != static_cast<int>(k)) holds_[p] = 0, on_plane_[p] = 0;  // a new contact
      const Eigen::Vector3d local = to_shape * x;
      if (!stuck) {
        enterThroughItsFace(obstacle.shape, start_poses[k].inverse(), body.stepStart(), q, local,
                            surface, normal);
      }
      contacts_[k].penetration = std::max(contacts_[k].penetration, (surface - local).norm());
      const Eigen::Vector3d on_surface = obstacle.pose * surface;
      obstacle_[p] = static_cast<int>(k);
      point_[p] = surface;
      normal_[p] = normal;
      const Eigen::Vector3d change =
          stuck ? Eigen::Vector3d::Zero()
                : landingChange(body, q, (on_surface - to_start * on_surface) / dt,
                                obstacle.pose.linear() * normal, settings);
      putBack(body, q, x, on_surface, change, dt);
    }
    if (!embedded_) continue;
    grant(position_requests_, body.mutablePositions());
    settleEmbedded(body, obstacle, static_cast<int>(k));
  }
  pushFacesOut(body, obstacles, start_poses, dt);
  recordNodePlaces(body, obstacles);
  const int touching = countTouching(body, obstacles);
  // Touching several obstacles or faces, or held otherwise, a body is not moved whole: what
  // slides on them slides on their planes in the next solve.
  if (!takenWhole(body)) {
    for (size_t p = 0; p < points_.size(); ++p) {
      if (!holds_[p] || slip_[p].isZero(0.0)) continue;
      slideOnPlane(static_cast<int>(p), Eigen::Vector3d::Zero());
      slip_[p].setZero();
    }
  }
  return touching;
}

}  // namespace deformable_sim::core
