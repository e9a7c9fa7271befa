#include "deformable_sim/core/contact/body_contact.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>

#include "deformable_sim/core/base/parallel_for.h"
#include "deformable_sim/core/contact/edge_edge.h"
#include "deformable_sim/core/contact/node_triangle.h"
#include "deformable_sim/core/geometry/triangle_mesh.h"
#include "deformable_sim/core/geometry/triangle_mesh_shape.h"

namespace deformable_sim::core {

namespace {

/// A node counts as touching a triangle it sank behind by up to this fraction of the shortest
/// edge of the triangle's body, however it got there; deeper, only if it came through the
/// triangle within the step. A quarter edge is less than any part of the body is thick.
constexpr double kShallowFraction = 0.25;

/// How far the contact's node side is behind its triangle side now, m (zero: not behind).
double depthLeft(const BodyList& bodies, const BodyContact::Contact& c) {
  return std::max(0.0, -c.normal.dot(c.node.of(bodies[c.node_body].positions()) -
                                     c.triangle.of(bodies[c.triangle_body].positions())));
}

}  // namespace

BodyContact::BodyContact(BodyList& bodies, const ContactSettings& settings,
                         const std::vector<bool>& with_bodies, const std::vector<bool>& with_self)
    : settings_(settings), with_bodies_(with_bodies), with_self_(with_self) {
  for (size_t b = 0; b < bodies.size(); ++b) {
    surfaces_.emplace_back();
    participants_.emplace_back();
    if (!with_bodies_[b] && !with_self_[b]) continue;
    surfaces_.back().emplace(bodies[b].mesh(), bodies[b].positions(), with_self_[b]);
    participants_.back() = bodies[b].contactParticipant();
  }
  reserveContacts();
  loads_.resize(bodies.size() * bodies.size());
}

void BodyContact::embed(int b, const EmbeddedSurface& surface, const Body& body) {
  if (!surfaces_[b]) return;
  surfaces_[b].emplace(surface, body.positions());
  reserveContacts();
}

void BodyContact::reserveContacts() {
  size_t points = 0;
  for (const std::optional<BodySurface>& surface : surfaces_) {
    if (surface) points += surface->nodes().size() + kEdgeHits * surface->edges().size();
  }
  contacts_.reserve(points);
  found_.resize(surfaces_.size());
  for (size_t b = 0; b < surfaces_.size(); ++b) {
    if (!surfaces_[b]) continue;
    found_[b].reserve(surfaces_[b]->nodes().size() + kEdgeHits * surfaces_[b]->edges().size());
  }
  warm_.resize(surfaces_.size());
  for (size_t b = 0; b < surfaces_.size(); ++b) {
    if (!surfaces_[b]) continue;
    const std::vector<int>& corners = surfaces_[b]->nodes();
    const int count = corners.empty() ? 0 : *std::max_element(corners.begin(), corners.end()) + 1;
    warm_[b].assign(count, Warm{});
  }
  node_contact_.resize(surfaces_.size());
  for (size_t b = 0; b < surfaces_.size(); ++b) node_contact_[b].assign(warm_[b].size(), -1);
  twice_found_.reserve(contacts_.capacity());
  corner_kept_.resize(surfaces_.size());
  kept_corners_.resize(surfaces_.size());
  for (size_t b = 0; b < surfaces_.size(); ++b) {
    corner_kept_[b].assign(warm_[b].size(), kNotKept);
    kept_corners_[b].clear();
    kept_corners_[b].reserve(warm_[b].size());
  }
}

BodyContact::Overlap BodyContact::deepestOverlap() const {
  Overlap deepest;
  for (size_t of = 0; of < surfaces_.size(); ++of) {
    if (!surfaces_[of] || !with_bodies_[of]) continue;
    const BodySurface& surface = *surfaces_[of];
    TriangleMesh mesh;
    for (size_t c = 0; c * 3 < static_cast<size_t>(surface.start().size()); ++c) {
      mesh.vertices.emplace_back(surface.start().segment<3>(3 * c));
    }
    for (const Triangle& t : surface.triangles()) mesh.triangles.emplace_back(t[0], t[1], t[2]);
    std::optional<TriangleMeshShape> shape;
    try {
      shape.emplace(std::move(mesh));
    } catch (const std::invalid_argument&) {
      continue;  // not a mesh a point can be inside of
    }
    if (!shape->closed()) continue;
    for (size_t inside = 0; inside < surfaces_.size(); ++inside) {
      if (inside == of || !surfaces_[inside] || !with_bodies_[inside]) continue;
      const BodySurface& other = *surfaces_[inside];
      for (int c : other.nodes()) {
        const double depth = -shape->signedDistance(other.start().segment<3>(3 * c));
        if (depth > deepest.depth) {
          deepest = {static_cast<int>(inside), static_cast<int>(of), depth};
        }
      }
    }
  }
  return deepest;
}

double BodyContact::tolerance(int a, int b) const {
  return 0.01 * std::min(surfaces_[a]->size(), surfaces_[b]->size());
}

bool BodyContact::couldHaveMovedIn() const {
  // A node found clear was further than the pair's tolerance in front of every triangle; one
  // found touching was left within kTarget of it. Moved by less than half of that in the round,
  // on both sides, none can be deeper than the position passes leave them.
  double moved = 0.0, tightest = std::numeric_limits<double>::infinity();
  for (size_t a = 0; a < surfaces_.size(); ++a) {
    if (!surfaces_[a]) continue;
    moved = std::max(moved, participants_[a]->largestMove());
    for (size_t b = a; b < surfaces_.size(); ++b) {
      if (surfaces_[b] && touches(static_cast<int>(a), static_cast<int>(b))) {
        tightest = std::min(tightest, tolerance(static_cast<int>(a), static_cast<int>(b)));
      }
    }
  }
  return !(2.0 * moved < kTarget * tightest);
}

bool BodyContact::touches(int a, int b) const {
  return a == b ? bool(with_self_[a]) : with_bodies_[a] && with_bodies_[b];
}

bool BodyContact::prefer(const Candidate& hit, const Candidate& best, double tie) const {
  if (hit.rank != best.rank) return hit.rank < best.rank;
  if (!settings_.one_problem || std::abs(hit.depth - best.depth) > tie) {
    return hit.depth < best.depth;
  }
  if (std::abs(hit.facing - best.facing) > kFacingTie) return hit.facing > best.facing;
  return hit.last && !best.last;
}

void BodyContact::findContact(int a, int i, std::vector<Contact>& found) const {
  const BodySurface& mine = *surfaces_[a];
  SweptNode node{mine.start().segment<3>(3 * i), mine.now(i)};
  Contact best;
  Candidate chosen;
  // Out of the body at the node (only the one problem weighs how squarely it faces a triangle).
  const Eigen::Vector3d out =
      settings_.one_problem ? mine.outwardAt(i).normalized() : Eigen::Vector3d::Zero();
  const Warm& last = warm_[a][i];
  for (int b = 0; b < static_cast<int>(surfaces_.size()); ++b) {
    if (!surfaces_[b] || !touches(a, b)) continue;
    const BodySurface& other = *surfaces_[b];
    const double skin = tolerance(a, b);
    const double tie = settings_.one_problem ? kTie * skin : 0.0;
    Box3 box(node.start.cwiseMin(node.end), node.start.cwiseMax(node.end));
    box = Box3(box.min().array() - skin, box.max().array() + skin);
    other.tree().query(box, [&](int t) {
      const Triangle& tri = other.triangles()[t];
      if (a == b &&
          (other.adjacent(i, tri[0]) || other.adjacent(i, tri[1]) || other.adjacent(i, tri[2]))) {
        return;  // its own elements: their stiffness keeps them apart
      }
      SweptTriangle swept;
      for (int k = 0; k < 3; ++k) {
        swept.start[k] = other.start().segment<3>(3 * tri[k]);
        swept.end[k] = other.now(tri[k]);
      }
      NodeTriangleHit hit;
      const double shallow = kShallowFraction * other.shortestEdge();
      if (!nodeHitsTriangle(node, swept, skin, shallow, &hit)) return;
      Candidate candidate;
      candidate.rank = !(hit.depth > tie) ? 2 : hit.crossed ? 0 : 1;
      candidate.depth = std::abs(hit.depth);
      candidate.facing = -hit.normal.dot(out);
      candidate.last = last.triangle_body == b && last.corners == tri;
      if (!prefer(candidate, chosen, tie)) return;
      chosen = candidate;
      best.triangle_body = b;
      best.triangle = other.trianglePoint(tri, {hit.weights[0], hit.weights[1], hit.weights[2]});
      best.triangle_corners = {
          3, {tri[0], tri[1], tri[2]}, {hit.weights[0], hit.weights[1], hit.weights[2]}};
      best.normal = hit.normal;
    });
  }
  if (chosen.rank == 3) return;
  best.node_body = a;
  best.node_corners = {1, {i, 0, 0}, {1.0, 0.0, 0.0}};
  best.node = mine.corner(i);
  add(best, found);
}

void BodyContact::add(Contact c, std::vector<Contact>& found) const {
  c.node_moves = participants_[c.node_body]->movable(c.node) >= kMovable;
  c.triangle_moves = participants_[c.triangle_body]->movable(c.triangle) >= kMovable;
  found.push_back(c);
}

Eigen::Vector3d BodyContact::outwardAt(int b, const SurfaceEdge& edge) const {
  Eigen::Vector3d outward = Eigen::Vector3d::Zero();
  for (int k = 0; k < 2; ++k) {
    const Triangle& t = surfaces_[b]->triangles()[edge.triangles[k]];
    const BodySurface& surface = *surfaces_[b];
    const Eigen::Vector3d corner = surface.now(t[0]);
    const Eigen::Vector3d normal = (surface.now(t[1]) - corner).cross(surface.now(t[2]) - corner);
    if (normal.norm() > 0.0) outward += normal.normalized();
  }
  return outward;
}

void BodyContact::findEdgeContacts(int a, int e, std::vector<Contact>& found) const {
  const BodySurface& mine = *surfaces_[a];
  const SurfaceEdge& edge = mine.edges()[e];
  SweptEdge swept;
  for (int k = 0; k < 2; ++k) {
    swept.start[k] = mine.start().segment<3>(3 * edge.nodes[k]);
    swept.end[k] = mine.now(edge.nodes[k]);
  }
  const Eigen::Vector3d outward = outwardAt(a, edge);
  int hits = 0;
  for (int b = a; b < static_cast<int>(surfaces_.size()); ++b) {
    if (!surfaces_[b] || !touches(a, b)) continue;
    const BodySurface& other = *surfaces_[b];
    const double skin = tolerance(a, b);
    Box3 box(swept.start[0].cwiseMin(swept.end[0]).cwiseMin(swept.start[1]).cwiseMin(swept.end[1]),
             swept.start[0].cwiseMax(swept.end[0]).cwiseMax(swept.start[1]).cwiseMax(swept.end[1]));
    box = Box3(box.min().array() - skin, box.max().array() + skin);
    other.edgeTree().query(box, [&](int f) {
      const SurfaceEdge& across = other.edges()[f];
      if (hits == kEdgeHits) return;
      if (a == b && (f <= e || mine.adjacent(edge.nodes[0], across.nodes[0]) ||
                     mine.adjacent(edge.nodes[0], across.nodes[1]) ||
                     mine.adjacent(edge.nodes[1], across.nodes[0]) ||
                     mine.adjacent(edge.nodes[1], across.nodes[1]))) {
        return;  // each pair once; and its own elements' stiffness keeps them apart
      }
      SweptEdge them;
      for (int k = 0; k < 2; ++k) {
        them.start[k] = other.start().segment<3>(3 * across.nodes[k]);
        them.end[k] = other.now(across.nodes[k]);
      }
      EdgeEdgeHit hit;
      const double shallow = kShallowFraction * std::min(mine.shortestEdge(), other.shortestEdge());
      if (!edgesMeet(swept, them, outward, outwardAt(b, across), skin, shallow, &hit)) return;
      Contact c;
      c.node_body = a;
      c.triangle_body = b;
      c.node = mine.edgePoint(edge, hit.s);
      c.triangle = other.edgePoint(across, hit.t);
      c.node_corners = {2, {edge.nodes[0], edge.nodes[1], 0}, {1.0 - hit.s, hit.s, 0.0}};
      c.triangle_corners = {2, {across.nodes[0], across.nodes[1], 0}, {1.0 - hit.t, hit.t, 0.0}};
      c.normal = hit.normal;
      add(c, found);
      ++hits;
    });
  }
}

double BodyContact::gap(const Contact& c) const {
  return c.normal.dot(participants_[c.node_body]->position(c.node) -
                      participants_[c.triangle_body]->position(c.triangle));
}

void BodyContact::shift(Contact& c, const Eigen::Vector3d& amount) {
  if (c.node_moves) participants_[c.node_body]->nudge(c.node, amount);
  if (c.triangle_moves) participants_[c.triangle_body]->nudge(c.triangle, -amount);
}

void BodyContact::separate(std::vector<StepReport>& reports) {
  for (int pass = 0; pass < kPositionPasses; ++pass) {
    bool settled = true;
    for (Contact& c : contacts_) {
      const double depth = -gap(c);
      if (!(depth > 0.0)) continue;
      if (depth > kTarget * tolerance(c.node_body, c.triangle_body)) settled = false;
      const double w =
          (c.node_moves ? participants_[c.node_body]->nudgeCompliance(c.node, c.normal) : 0.0) +
          (c.triangle_moves ? participants_[c.triangle_body]->nudgeCompliance(c.triangle, c.normal)
                            : 0.0);
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

void BodyContact::measureDepths(const BodyList& bodies) {
  const size_t n = surfaces_.size();
  for (ContactLoad& load : loads_) load.depth = 0.0;
  for (const Contact& c : contacts_) {
    const double left = depthLeft(bodies, c);
    for (size_t pair : {c.node_body * n + c.triangle_body, c.triangle_body * n + c.node_body}) {
      loads_[pair].depth = std::max(loads_[pair].depth, left);
    }
  }
}

double BodyContact::startGap(const Contact& c) const {
  return c.normal.dot(c.node.of(surfaces_[c.node_body]->nodeStart()) -
                      c.triangle.of(surfaces_[c.triangle_body]->nodeStart()));
}

void BodyContact::apply(Contact& c, const Eigen::Vector3d& impulse) {
  // An impulse changes the step's velocities, and so its end positions by dt times as much
  // (ContactParticipant::push): the step stays an implicit Euler step, x = x0 + dt v.
  ContactParticipant& node = *participants_[c.node_body];
  ContactParticipant& triangle = *participants_[c.triangle_body];
  if (c.node_moves) node.push(c.node, impulse, c.local, c.node_kept);
  if (c.triangle_moves) triangle.push(c.triangle, -impulse, c.local, c.triangle_kept);
}

double BodyContact::compliance(const Contact& c, const Eigen::Vector3d& direction) const {
  return direction.dot(c.compliance * direction);
}

void BodyContact::update(Contact& c, double dt) {
  const double w = compliance(c, c.normal);
  if (!(w > 0.0)) return;  // both held: nothing can move
  // The normal first: approaching no faster than closes the gap the pair had at the step's
  // start, it ends the step touching; a pair that started inside only stops approaching
  // (separate() does the rest). An impulse only pushes.
  const ContactParticipant& node = *participants_[c.node_body];
  const ContactParticipant& triangle = *participants_[c.triangle_body];
  const Eigen::Vector3d relative = node.velocity(c.node) - triangle.velocity(c.triangle);
  const double target = -std::max(c.start_gap, 0.0) / dt;
  const double impulse = std::max(0.0, c.impulse + (target - c.normal.dot(relative)) / w);
  Eigen::Vector3d change = (impulse - c.impulse) * c.normal;
  c.impulse = impulse;
  // Then friction, against the slip the new normal impulse leaves, kept in the cone.
  if (settings_.friction > 0.0) {
    Eigen::Vector3d sliding = relative + c.compliance * change;
    sliding -= sliding.dot(c.normal) * c.normal;
    const double speed = sliding.norm();
    const Eigen::Vector3d direction =
        speed > 0.0 ? Eigen::Vector3d(sliding / speed) : Eigen::Vector3d::Zero();
    const double wt = speed > 0.0 ? compliance(c, direction) : 0.0;
    const Eigen::Vector3d wanted =
        wt > 0.0 ? Eigen::Vector3d(c.friction - speed / wt * direction) : c.friction;
    const double cone = settings_.friction * c.impulse;
    const Eigen::Vector3d friction =
        wanted.norm() <= cone ? wanted : Eigen::Vector3d(cone / wanted.norm() * wanted);
    change += friction - c.friction;
    c.friction = friction;
  }
  if (change.isZero(0.0)) return;
  apply(c, change);
  // How much this update moved the pair: the sweeps stop when no update moves any by much.
  largest_change_ = std::max(largest_change_, (c.compliance * change).norm());
}

Eigen::Vector3d BodyContact::lastImpulse(int i) const { return lastImpulseOf(contacts_[i]); }

Eigen::Vector3d BodyContact::lastImpulseOf(const Contact& c) const {
  if (c.node_corners.count != 1) return Eigen::Vector3d::Zero();  // edges that meet
  const Warm& last = warm_[c.node_body][c.node_corners.ids[0]];
  return last.triangle_body == c.triangle_body ? last.impulse : Eigen::Vector3d::Zero();
}

void BodyContact::startFromLastStep(Contact& c) {
  // Last step's impulse on the pair, turned into this step's normal and cone.
  const Eigen::Vector3d last = lastImpulseOf(c);
  c.impulse = std::max(0.0, c.normal.dot(last));
  Eigen::Vector3d friction = last - c.normal.dot(last) * c.normal;
  const double cone = settings_.friction * c.impulse;
  if (friction.norm() > cone) friction *= cone / friction.norm();
  c.friction = friction;
  const Eigen::Vector3d impulse = c.impulse * c.normal + c.friction;
  if (!impulse.isZero(0.0)) apply(c, impulse);
}

void BodyContact::keepForNextStep() {
  for (std::vector<Warm>& warm : warm_) {
    for (Warm& w : warm) w.triangle_body = -1;
  }
  for (const Contact& c : contacts_) {
    if (c.node_corners.count != 1) continue;
    const std::array<int, 3>& t = c.triangle_corners.ids;
    warm_[c.node_body][c.node_corners.ids[0]] = {
        c.triangle_body, {t[0], t[1], t[2]}, c.impulse * c.normal + c.friction};
  }
}

int BodyContact::keepPoint(int b, const SurfaceCorners& corners) {
  ContactParticipant& body = *participants_[b];
  std::array<int, 3> kept{};
  for (int k = 0; k < corners.count; ++k) {
    int& corner = corner_kept_[b][corners.ids[k]];
    if (corner == kNotKept) {
      corner = body.keepCorner(corners.ids[k], surfaces_[b]->corner(corners.ids[k]));
      kept_corners_[b].push_back(corners.ids[k]);
    }
    if (corner < 0) return -1;
    kept[k] = corner;
  }
  if (corners.count == 1 && corners.weights[0] == 1.0) return kept[0];
  return body.keepSum(kept.data(), corners.weights.data(), corners.count);
}

void BodyContact::prepareAnswers(int b) {
  ContactParticipant& body = *participants_[b];
  for (int corner : kept_corners_[b]) corner_kept_[b][corner] = kNotKept;
  kept_corners_[b].clear();
  // Each side sums its nodes' answers once for all the passes, and its compliance from them.
  // (A node that starts touching after a point was kept makes that point's sum stale: it is
  // then answered node by node in this round.)
  for (Contact& c : contacts_) {
    if (c.node_body == b) c.node_kept = c.local ? -1 : keepPoint(b, c.node_corners);
    if (c.triangle_body == b) c.triangle_kept = c.local ? -1 : keepPoint(b, c.triangle_corners);
  }
  for (Contact& c : contacts_) {
    if (c.node_body == b && c.node_moves) {
      c.node_compliance = body.compliance(c.node, c.local, c.node_kept);
    }
    if (c.triangle_body == b && c.triangle_moves) {
      c.triangle_compliance = body.compliance(c.triangle, c.local, c.triangle_kept);
    }
  }
}

void BodyContact::settleVelocities(double dt, int threads) {
  for (Contact& c : contacts_) {
    c.start_gap = startGap(c);
    // Against a surface that cannot move there (held all over: a plate driven as a whole; or
    // held about the point) the free side answers node by node: its whole-body answer, pinned
    // between such surfaces, makes the passes converge too slowly to keep it out of them.
    c.local = !c.node_moves || !c.triangle_moves;
    c.node_compliance.setZero();
    c.triangle_compliance.setZero();
  }
  // Each body its own answers, a body to a thread.
  parallelForEach(threads, 0, static_cast<int>(participants_.size()), [&](int b) {
    if (surfaces_[b]) prepareAnswers(b);
  });
  // On a body touching itself the node's and the triangle's answers to each other are left out:
  // the passes then take smaller steps, which only slows them.
  for (Contact& c : contacts_) c.compliance = c.node_compliance + c.triangle_compliance;
  for (Contact& c : contacts_) startFromLastStep(c);
  passes_ = 0;
  for (int pass = 0; pass < kVelocityPasses; ++pass) {
    largest_change_ = 0.0;
    for (Contact& c : contacts_) update(c, dt);
    ++passes_;
    if (largest_change_ <= kVelocityTolerance) break;
  }
  keepForNextStep();
}

void BodyContact::resolve(BodyList& bodies, double dt, int threads,
                          std::vector<StepReport>& reports) {
  dt_ = dt;
  // An impulse moves the whole body, so nodes that were clear when the contacts were found can
  // be pressed into another surface by it (a cube's sides bulging as its top is pushed). A last
  // round finds the contacts again and only puts back what is inside, node by node.
  for (int round = 0; round < kRounds; ++round) {
    const bool last = round == kRounds - 1;
    if (last && !couldHaveMovedIn()) break;
    findContacts(bodies, round == 0, threads);
    if (round == 0) {
      countContacts(reports);
      startLoads();
    }
    if (!last) settleVelocities(dt, threads);
    if (round == 0) addContactForces(dt);
    separate(reports);
    parallelFor(threads, 0, static_cast<int>(bodies.size()), [&](int b) {
      if (surfaces_[b]) participants_[b]->end();
    });
  }
  for (int b = 0; b < static_cast<int>(bodies.size()); ++b) {
    if (!surfaces_[b]) continue;
    surfaces_[b]->setStart(bodies[b].positions());
    reports[b].body_contact_solves = participants_[b]->solves();
  }
}

void BodyContact::findContacts(BodyList& bodies, bool new_step, int threads) {
  const int n = static_cast<int>(bodies.size());
  // Each body by itself, then each body's contacts by itself, put together in body order: the
  // same contacts in the same order on any thread count.
  parallelForEach(threads, 0, n, [&](int b) {
    if (!surfaces_[b]) return;
    participants_[b]->begin(dt_, new_step);
    double skin = std::numeric_limits<double>::infinity();
    for (int o = 0; o < n; ++o) {
      if (surfaces_[o] && touches(b, o)) skin = std::min(skin, tolerance(b, o));
    }
    surfaces_[b]->sweep(bodies[b].positions(),
                        skin == std::numeric_limits<double>::infinity() ? 0.0 : skin);
  });
  parallelForEach(threads, 0, n, [&](int a) {
    std::vector<Contact>& found = found_[a];
    found.clear();
    if (!surfaces_[a]) return;
    for (int i : surfaces_[a]->nodes()) findContact(a, i, found);
    for (int e = 0; e < static_cast<int>(surfaces_[a]->edges().size()); ++e) {
      findEdgeContacts(a, e, found);
    }
  });
  contacts_.clear();
  for (const std::vector<Contact>& found : found_) {
    contacts_.insert(contacts_.end(), found.begin(), found.end());  // within the reserve
  }
}

void BodyContact::dropTwiceFound() {
  const int n = static_cast<int>(contacts_.size());
  for (int i = 0; i < n; ++i) {
    const Contact& c = contacts_[i];
    if (c.node_corners.count == 1) node_contact_[c.node_body][c.node_corners.ids[0]] = i;
  }
  // The node of contact c's triangle that c sits on, if any, and that node's own contact.
  const auto partner = [&](const Contact& c) {
    for (int k = 0; k < c.triangle_corners.count; ++k) {
      if (c.triangle_corners.weights[k] >= kOnTheNode)
        return node_contact_[c.triangle_body][c.triangle_corners.ids[k]];
    }
    return -1;
  };
  const auto onNodes = [](const SurfaceCorners& edge) {
    return std::max(edge.weights[0], edge.weights[1]) >= kOnTheNode;
  };
  // How squarely contact c's node faces the triangle it found (1: head on).
  const auto facing = [&](const Contact& c) {
    const Eigen::Vector3d out = surfaces_[c.node_body]->outwardAt(c.node_corners.ids[0]);
    return out.norm() > 0.0 ? -c.normal.dot(out.normalized()) : 0.0;
  };
  // Whether c's node touched c's other body last step (on whichever triangle).
  const auto hadLastStep = [&](const Contact& c) {
    return warm_[c.node_body][c.node_corners.ids[0]].triangle_body == c.triangle_body;
  };
  twice_found_.assign(contacts_.size(), 0);
  for (int i = 0; i < n; ++i) {
    const Contact& c = contacts_[i];
    if (c.node_corners.count == 2) {  // edges that meet at their ends: nodes that touch
      twice_found_[i] = onNodes(c.node_corners) && onNodes(c.triangle_corners);
      continue;
    }
    const int j = partner(c);
    if (j <= i || contacts_[j].triangle_body != c.node_body || partner(contacts_[j]) != i) continue;
    // Of the pair, the one whose node faces its triangle more squarely; if about as squarely,
    // the one kept last step, else the first found.
    const Contact& d = contacts_[j];
    const bool take_d = std::abs(facing(d) - facing(c)) > kFacingTie
                            ? facing(d) > facing(c)
                            : hadLastStep(d) && !hadLastStep(c);
    twice_found_[take_d ? i : j] = 1;
  }
  int kept = 0;
  for (int i = 0; i < n; ++i) {
    const Contact& c = contacts_[i];
    if (c.node_corners.count == 1) node_contact_[c.node_body][c.node_corners.ids[0]] = -1;
    if (!twice_found_[i]) contacts_[kept++] = c;
  }
  contacts_.resize(kept);
}

void BodyContact::countContacts(std::vector<StepReport>& reports) const {
  for (const Contact& c : contacts_) {
    if (c.node_body == c.triangle_body) {
      ++reports[c.node_body].self_contacts;
    } else {
      ++reports[c.node_body].body_contacts;
      ++reports[c.triangle_body].body_contacts;
    }
  }
}

void BodyContact::startLoads() {
  for (ContactLoad& load : loads_) load = ContactLoad{};
  const size_t n = surfaces_.size();
  const auto addPoint = [](ContactLoad& load, const Eigen::Vector3d& p, double depth) {
    load.centre = (load.points * load.centre + p) / (load.points + 1);
    ++load.points;
    load.penetration = std::max(load.penetration, depth);
  };
  for (const Contact& c : contacts_) {
    const double depth = std::max(0.0, -gap(c));
    addPoint(loads_[c.node_body * n + c.triangle_body],
             participants_[c.node_body]->position(c.node), depth);
    // A body touching itself counts the node alone.
    if (c.node_body == c.triangle_body) continue;
    addPoint(loads_[c.triangle_body * n + c.node_body],
             participants_[c.triangle_body]->position(c.triangle), depth);
  }
}

void BodyContact::addContactForces(double dt) {
  const size_t n = surfaces_.size();
  for (const Contact& c : contacts_) {
    const Eigen::Vector3d force = (c.impulse * c.normal + c.friction) / dt;  // on the node
    const Eigen::Vector3d at_node = participants_[c.node_body]->position(c.node);
    const Eigen::Vector3d at_triangle = participants_[c.triangle_body]->position(c.triangle);
    ContactLoad& on_node = loads_[c.node_body * n + c.triangle_body];
    on_node.force += force;
    on_node.torque += at_node.cross(force);
    ContactLoad& on_triangle = loads_[c.triangle_body * n + c.node_body];
    on_triangle.force -= force;
    on_triangle.torque -= at_triangle.cross(force);
  }
}

void BodyContact::find(BodyList& bodies, double dt, int threads, std::vector<StepReport>& reports) {
  dt_ = dt;
  findContacts(bodies, true, threads);
  dropTwiceFound();
  countContacts(reports);
  startLoads();
  for (Contact& c : contacts_) c.start_gap = startGap(c);
}

void BodyContact::takeImpulse(int i, const Eigen::Vector3d& impulse) {
  Contact& c = contacts_[i];
  c.impulse = c.normal.dot(impulse);
  c.friction = impulse - c.impulse * c.normal;
}

void BodyContact::finishStep(const BodyList& bodies, double dt, std::vector<StepReport>& reports) {
  addContactForces(dt);
  keepForNextStep();
  for (const Contact& c : contacts_) {
    const double left = depthLeft(bodies, c);
    for (int b : {c.node_body, c.triangle_body}) {
      reports[b].body_penetration = std::max(reports[b].body_penetration, left);
    }
  }
  for (int b = 0; b < static_cast<int>(bodies.size()); ++b) {
    if (!surfaces_[b]) continue;
    surfaces_[b]->setStart(bodies[b].positions());
    reports[b].body_contact_solves = participants_[b]->solves();
  }
}

}  // namespace deformable_sim::core
