#include "deformable_sim/core/body_contact.h"

#include <algorithm>
#include <limits>

#include "deformable_sim/core/node_triangle.h"

namespace deformable_sim::core {

namespace {

/// A node counts as touching a triangle it sank behind by up to this fraction of the shortest
/// edge of the triangle's body, however it got there; deeper, only if it came through the
/// triangle within the step. A quarter edge is less than any part of the body is thick.
constexpr double kShallowFraction = 0.25;

Eigen::Vector3d startOf(const BodySurface& surface, const SurfacePoint& point) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int k = 0; k < point.count; ++k) {
    p += point.weights[k] * surface.start().segment<3>(3 * point.nodes[k]);
  }
  return p;
}

SurfacePoint nodePoint(int i) {
  SurfacePoint point;
  point.nodes = {i, i, i};
  point.weights = {1.0, 0.0, 0.0};
  point.count = 1;
  return point;
}

}  // namespace

BodyContact::BodyContact(const std::vector<Body>& bodies, const ContactSettings& settings,
                         const std::vector<bool>& with_bodies, const std::vector<bool>& with_self)
    : settings_(settings), with_bodies_(with_bodies), with_self_(with_self) {
  size_t surface_nodes = 0;
  for (size_t b = 0; b < bodies.size(); ++b) {
    surfaces_.emplace_back();
    participants_.emplace_back();
    if (!with_bodies_[b] && !with_self_[b]) continue;
    surfaces_.back().emplace(bodies[b].mesh(), bodies[b].positions(), with_self_[b]);
    participants_.back().emplace(bodies[b]);
    surface_nodes += surfaces_.back()->nodes().size();
  }
  contacts_.reserve(surface_nodes);
}

double BodyContact::tolerance(int a, int b) const {
  return 0.01 * std::min(surfaces_[a]->size(), surfaces_[b]->size());
}

bool BodyContact::touches(int a, int b) const {
  return a == b ? bool(with_self_[a]) : with_bodies_[a] && with_bodies_[b];
}

void BodyContact::findContact(int a, int i) {
  const ContactParticipant& nodes = *participants_[a];
  SweptNode node{surfaces_[a]->start().segment<3>(3 * i), nodes.position(nodePoint(i))};
  Contact best;
  double best_depth = std::numeric_limits<double>::infinity();
  bool best_crossed = false;
  for (int b = 0; b < static_cast<int>(surfaces_.size()); ++b) {
    if (!surfaces_[b] || !touches(a, b)) continue;
    const BodySurface& other = *surfaces_[b];
    const double skin = tolerance(a, b);
    Box3 box(node.start.cwiseMin(node.end), node.start.cwiseMax(node.end));
    box = Box3(box.min().array() - skin, box.max().array() + skin);
    const ContactParticipant& corners = *participants_[b];
    other.tree().query(box, [&](int t) {
      const Triangle& tri = other.triangles()[t];
      if (a == b &&
          (other.adjacent(i, tri[0]) || other.adjacent(i, tri[1]) || other.adjacent(i, tri[2]))) {
        return;  // its own elements: their stiffness keeps them apart
      }
      SweptTriangle swept;
      for (int k = 0; k < 3; ++k) {
        swept.start[k] = other.start().segment<3>(3 * tri[k]);
        swept.end[k] = corners.position(nodePoint(tri[k]));
      }
      NodeTriangleHit hit;
      const double shallow = kShallowFraction * other.shortestEdge();
      if (!nodeHitsTriangle(node, swept, skin, shallow, &hit)) return;
      // A triangle the node came through beats one it only ended near; then the shallowest.
      if (hit.crossed != best_crossed ? !hit.crossed : !(hit.depth < best_depth)) return;
      best_depth = hit.depth;
      best_crossed = hit.crossed;
      best.triangle_body = b;
      best.triangle.nodes = tri;
      best.triangle.weights = {hit.weights[0], hit.weights[1], hit.weights[2]};
      best.triangle.count = 3;
      best.normal = hit.normal;
    });
  }
  if (best_depth == std::numeric_limits<double>::infinity()) return;
  best.node_body = a;
  best.node = nodePoint(i);
  contacts_.push_back(best);
}

double BodyContact::gap(const Contact& c) const {
  return c.normal.dot(participants_[c.node_body]->position(c.node) -
                      participants_[c.triangle_body]->position(c.triangle));
}

void BodyContact::shift(Contact& c, const Eigen::Vector3d& amount) {
  participants_[c.node_body]->displace(c.node, amount);
  participants_[c.triangle_body]->displace(c.triangle, -amount);
}

void BodyContact::separate(std::vector<StepReport>& reports) {
  for (int pass = 0; pass < kPositionPasses; ++pass) {
    bool settled = true;
    for (Contact& c : contacts_) {
      const double depth = -gap(c);
      if (!(depth > 0.0)) continue;
      if (depth > kTarget * tolerance(c.node_body, c.triangle_body)) settled = false;
      const double w = participants_[c.node_body]->inverseMass(c.node, c.normal) +
                       participants_[c.triangle_body]->inverseMass(c.triangle, c.normal);
      if (!(w > 0.0)) continue;  // both held: nothing can move
      c.pushed += depth / w;
      shift(c, depth / w * c.normal);
    }
    if (settled) break;
  }
  for (const Contact& c : contacts_) {
    const double left = std::max(0.0, -gap(c));
    for (int b : {c.node_body, c.triangle_body}) {
      reports[b].body_penetration = std::max(reports[b].body_penetration, left);
    }
  }
}

Eigen::Vector3d BodyContact::slip(const Contact& c) const {
  const Eigen::Vector3d moved =
      (participants_[c.node_body]->position(c.node) - startOf(*surfaces_[c.node_body], c.node)) -
      (participants_[c.triangle_body]->position(c.triangle) -
       startOf(*surfaces_[c.triangle_body], c.triangle));
  return moved - moved.dot(c.normal) * c.normal;
}

void BodyContact::holdBySlip() {
  if (!(settings_.friction > 0.0)) return;
  for (Contact& c : contacts_) {
    const Eigen::Vector3d tangential = slip(c);
    const double length = tangential.norm();
    if (!(length > 0.0)) continue;
    const Eigen::Vector3d direction = tangential / length;
    const double w = participants_[c.node_body]->inverseMass(c.node, direction) +
                     participants_[c.triangle_body]->inverseMass(c.triangle, direction);
    if (!(w > 0.0)) continue;
    // Sticks when the slip's shift is within the cone of the normal one; slides back by the
    // cone's edge otherwise.
    const double back = std::min(length / w, settings_.friction * c.pushed);
    shift(c, -back * direction);
  }
}

void BodyContact::settleVelocities(double dt) {
  for (int pass = 0; pass < kVelocityPasses; ++pass) {
    for (Contact& c : contacts_) {
      ContactParticipant& node = *participants_[c.node_body];
      ContactParticipant& triangle = *participants_[c.triangle_body];
      const double approach = -c.normal.dot(node.velocity(c.node) - triangle.velocity(c.triangle));
      const double w =
          node.inverseMass(c.node, c.normal) + triangle.inverseMass(c.triangle, c.normal);
      if (!(approach > 0.0) || !(w > 0.0)) continue;
      c.impulse += approach / w;
      node.push(c.node, approach / w * c.normal);
      triangle.push(c.triangle, -approach / w * c.normal);
    }
  }
  if (!(settings_.friction > 0.0)) return;
  for (Contact& c : contacts_) {
    ContactParticipant& node = *participants_[c.node_body];
    ContactParticipant& triangle = *participants_[c.triangle_body];
    Eigen::Vector3d sliding = node.velocity(c.node) - triangle.velocity(c.triangle);
    sliding -= sliding.dot(c.normal) * c.normal;
    const double speed = sliding.norm();
    if (!(speed > 0.0)) continue;
    const Eigen::Vector3d direction = sliding / speed;
    const double w =
        node.inverseMass(c.node, direction) + triangle.inverseMass(c.triangle, direction);
    if (!(w > 0.0)) continue;
    const double cone = settings_.friction * (c.impulse + c.pushed / dt);
    const double stop = std::min(speed / w, cone);
    node.push(c.node, -stop * direction);
    triangle.push(c.triangle, stop * direction);
  }
}

void BodyContact::resolve(std::vector<Body>& bodies, double dt, std::vector<StepReport>& reports) {
  const int n = static_cast<int>(bodies.size());
  for (int b = 0; b < n; ++b) {
    if (!surfaces_[b]) continue;
    participants_[b]->begin(bodies[b]);
    double skin = std::numeric_limits<double>::infinity();
    for (int o = 0; o < n; ++o) {
      if (surfaces_[o] && touches(b, o)) skin = std::min(skin, tolerance(b, o));
    }
    surfaces_[b]->sweep(bodies[b].positions(),
                        skin == std::numeric_limits<double>::infinity() ? 0.0 : skin);
  }
  contacts_.clear();
  for (int a = 0; a < n; ++a) {
    if (!surfaces_[a]) continue;
    for (int i : surfaces_[a]->nodes()) findContact(a, i);
  }
  for (const Contact& c : contacts_) {
    if (c.node_body == c.triangle_body) {
      ++reports[c.node_body].self_contacts;
    } else {
      ++reports[c.node_body].body_contacts;
      ++reports[c.triangle_body].body_contacts;
    }
  }
  separate(reports);
  holdBySlip();
  settleVelocities(dt);
  for (int b = 0; b < n; ++b) {
    if (!surfaces_[b]) continue;
    participants_[b]->end(bodies[b]);
    surfaces_[b]->setStart(bodies[b].positions());
  }
}

}  // namespace deformable_sim::core
