#include "deformable_sim/core/contact.h"

#include <algorithm>

namespace deformable_sim::core {

namespace {

/// Passes over a body's touching vertices on one obstacle: their cells share nodes, so putting
/// one back moves its neighbours.
constexpr int kEmbeddedPasses = 8;

}  // namespace

ContactState::ContactState(int num_nodes)
    : points_(num_nodes),
      node_obstacle_(num_nodes, -1),
      node_place_(num_nodes, Eigen::Vector3d::Zero()),
      held_flag_(num_nodes, 0),
      held_weight_(num_nodes, 0.0),
      position_requests_(num_nodes),
      velocity_requests_(num_nodes) {
  for (int i = 0; i < num_nodes; ++i) {
    points_[i].nodes[0] = i;
    points_[i].weights[0] = 1.0;
    points_[i].count = 1;
  }
  held_.reserve(num_nodes);
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
  embedded_ = true;
  resizePoints();
}

void ContactState::resizePoints() {
  const size_t n = points_.size();
  obstacle_.assign(n, -1);
  point_.assign(n, Eigen::Vector3d::Zero());
  normal_.assign(n, Eigen::Vector3d::Zero());
  sticking_.assign(n, 0);
  point_held_.assign(n, 0);
  point_force_.assign(n, Eigen::Vector3d::Zero());
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

double ContactState::freeWeight(const Body& body, int p) const {
  const Point& point = points_[p];
  double free = 0.0;
  for (int k = 0; k < point.count; ++k) {
    if (!body.isConstrained(point.nodes[k])) free += point.weights[k];
  }
  return free;
}

bool ContactState::movable(const Body& body, int p) const {
  const Point& point = points_[p];
  if (point.count == 1) return !body.isConstrained(point.nodes[0]);
  return freeWeight(body, p) >= kMovable;
}

ContactState::Requests::Requests(int num_nodes)
    : weight(num_nodes, 0.0), sum(num_nodes, Eigen::Vector3d::Zero()) {
  touched.reserve(num_nodes);
}

void ContactState::request(const Body& body, int p, const Eigen::Vector3d& change,
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

void ContactState::hold(Body& body, const std::vector<PlacedShape>& obstacles) {
  held_.clear();
  for (size_t p = 0; p < points_.size(); ++p) {
    point_held_[p] = 0;
    // Only a point that sticks: holding a sliding one would stop it for a whole step, and a
    // frictionless block on a slope would creep down instead of sliding with g sin θ.
    const int k = obstacle_[p];
    if (k < 0 || !sticking_[p]) continue;
    const Point& point = points_[p];
    for (int j = 0; j < point.count; ++j) {
      const int i = point.nodes[j];
      if (node_obstacle_[i] != k) continue;  // its place was taken on another obstacle
      if (held_flag_[i]) {                   // by a neighbouring vertex in the same cell
        held_weight_[i] += point.weights[j];
        point_held_[p] = 1;
        continue;
      }
      if (body.isConstrained(i)) continue;
      body.holdNodeAt(i, obstacles[k].pose * node_place_[i]);
      held_.push_back(i);
      held_flag_[i] = 1;
      held_weight_[i] = point.weights[j];
      point_held_[p] = 1;
    }
  }
}

void ContactState::judgePatches(const Body& body, const std::vector<PlacedShape>& obstacles,
                                const ContactSettings& settings, double dt) {
  // Coulomb's law for the held points on one obstacle together: single points carry uneven parts
  // of the load, and judging each by itself lets some slip while the body sticks (it creeps) and
  // keeps others held while it slides (it stops).
  const Eigen::VectorXd& reactions = body.reactionForces();
  for (size_t p = 0; p < points_.size(); ++p) {
    if (!point_held_[p]) continue;
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
    const Eigen::Vector3d n = worldNormal(obstacles, static_cast<int>(p));
    const double pushing = r.dot(n);
    if (!(pushing > 0.0)) continue;
    Patch& patch = patches_[obstacle_[p]];
    patch.pushing += pushing;
    patch.sliding += r - pushing * n;
    patch.mass += mass;
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
  for (size_t p = 0; p < points_.size(); ++p) {
    // Points not held touch only if project() finds them inside again.
    if (!point_held_[p]) {
      obstacle_[p] = -1, sticking_[p] = 0;
      continue;
    }
    const int k = obstacle_[p];
    const Patch& patch = patches_[k];
    const Eigen::Vector3d n = worldNormal(obstacles, static_cast<int>(p));
    const Eigen::Vector3d& r = point_force_[p];
    const double pushing = r.dot(n);
    if (pushing > 0.0) {
      addForce(k, weighted(body.positions(), static_cast<int>(p)),
               pushing * n + patch.transmitted * (r - pushing * n));
      if (!patch.sticks) slideHeldNodes(body, static_cast<int>(p), patch.slip);
    }
    sticking_[p] = patch.sticks && pushing > 0.0;
    if (!sticking_[p]) obstacle_[p] = -1;  // it lifts off or slides: free
    point_held_[p] = 0;
  }
  for (int i : held_) {
    body.releaseNode(i);
    held_flag_[i] = 0;
  }
  held_.clear();
}

void ContactState::slideHeldNodes(Body& body, int p, const Eigen::Vector3d& slip) const {
  const Point& point = points_[p];
  for (int j = 0; j < point.count; ++j) {
    const int i = point.nodes[j];
    if (!held_flag_[i] || node_obstacle_[i] != obstacle_[p]) continue;
    body.mutableVelocities().segment<3>(3 * i) += point.weights[j] / held_weight_[i] * slip;
  }
}

Eigen::Vector3d ContactState::frictionChange(const Body& body, int p,
                                             const Eigen::Vector3d& obstacle_velocity,
                                             const Eigen::Vector3d& normal,
                                             const ContactSettings& settings) {
  const Eigen::Vector3d velocity = weighted(body.velocities(), p);
  Eigen::Vector3d relative = velocity - obstacle_velocity;
  const double into = -relative.dot(normal);
  if (!(into > 0.0)) {  // resting or leaving: it sticks if it does not slide
    sticking_[p] = sticking_[p] || (relative - relative.dot(normal) * normal).isZero(0.0);
    return Eigen::Vector3d::Zero();
  }
  relative += into * normal;
  if (settings.friction > 0.0) {
    const double sliding = relative.norm(), slowed = settings.friction * into;
    relative = sliding <= slowed ? Eigen::Vector3d::Zero()
                                 : Eigen::Vector3d(relative * (1.0 - slowed / sliding));
  }
  sticking_[p] = relative.isZero(0.0);
  return obstacle_velocity + relative - velocity;
}

void ContactState::settleEmbedded(Body& body, const PlacedShape& obstacle, int k) {
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

void ContactState::grantVelocities(Body& body, int k, double dt) {
  // What the obstacle gave each node, as a force on the body.
  for (int i : velocity_requests_.touched) {
    const Eigen::Vector3d change = velocity_requests_.sum[i] / velocity_requests_.weight[i];
    addForce(k, body.positions().segment<3>(3 * i), body.nodalMasses()[i] * change / dt);
  }
  grant(velocity_requests_, body.mutableVelocities());
}

void ContactState::recordNodePlaces(const Body& body, const std::vector<PlacedShape>& obstacles) {
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

void ContactState::putBack(Body& body, int p, const Eigen::Vector3d& x,
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

int ContactState::project(Body& body, const std::vector<PlacedShape>& obstacles,
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
      const double distance = signedDistance(obstacle.shape, to_shape * x, &surface, &normal);
      if (!(distance < 0.0)) continue;
      contacts_[k].penetration = std::max(contacts_[k].penetration, -distance);
      const Eigen::Vector3d on_surface = obstacle.pose * surface;
      // A point held at its place on this obstacle moved with it: it is inside by round-off
      // only, and still sticks.
      const bool stuck = obstacle_[p] == static_cast<int>(k) && sticking_[p];
      if (obstacle_[p] != static_cast<int>(k)) sticking_[p] = 0;  // a new contact
      obstacle_[p] = static_cast<int>(k);
      point_[p] = surface;
      normal_[p] = normal;
      const Eigen::Vector3d change =
          stuck ? Eigen::Vector3d::Zero()
                : frictionChange(body, q, (on_surface - to_start * on_surface) / dt,
                                 obstacle.pose.linear() * normal, settings);
      putBack(body, q, x, on_surface, change, dt);
    }
    if (!embedded_) continue;
    grant(position_requests_, body.mutablePositions());
    settleEmbedded(body, obstacle, static_cast<int>(k));
  }
  recordNodePlaces(body, obstacles);
  int touching = 0;
  for (ContactLoad& c : contacts_) c.points = 0, c.centre.setZero();
  for (size_t p = 0; p < points_.size(); ++p) {
    if (obstacle_[p] < 0) continue;
    ++touching;
    ++contacts_[obstacle_[p]].points;
    contacts_[obstacle_[p]].centre += weighted(body.positions(), static_cast<int>(p));
  }
  for (ContactLoad& c : contacts_) {
    if (c.points > 0) c.centre /= c.points;
  }
  return touching;
}

}  // namespace deformable_sim::core
