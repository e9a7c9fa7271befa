// ContactState's part for the edges and corners of box and mesh obstacles (see contact.h).
#include <algorithm>
#include <limits>

#include "deformable_sim/core/contact/contact.h"
#include "deformable_sim/core/geometry/triangle_separation.h"

namespace deformable_sim::core {

namespace {

/// Whether the obstacle has edges and corners: a box or a mesh.
bool hasFeatures(const Shape& shape) {
  return shape.kind == Shape::Kind::kBox || shape.kind == Shape::Kind::kMesh;
}

/// The box's or mesh's bounding box in the world, grown by `margin` m.
Eigen::AlignedBox3d boundsOf(const PlacedShape& obstacle, double margin) {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero(), half = 0.5 * obstacle.shape.size;
  if (obstacle.shape.kind == Shape::Kind::kMesh) {
    const Eigen::AlignedBox3d& local = obstacle.shape.mesh->bounds();
    centre = local.center();
    half = 0.5 * local.sizes();
  }
  const Eigen::Vector3d middle = obstacle.pose * centre;
  const Eigen::Vector3d reach =
      obstacle.pose.linear().cwiseAbs() * half + Eigen::Vector3d::Constant(margin);
  return {middle - reach, middle + reach};
}

}  // namespace

void ContactState::pushFacesOut(FiniteElementBody& body, const std::vector<PlacedShape>& obstacles,
                                const std::vector<Eigen::Isometry3d>& start_poses, double dt) {
  for (int i : face_nodes_) face_obstacle_[i] = -1;
  face_nodes_.clear();
  face_touches_.clear();
  bool placed = false;
  for (size_t k = 0; k < obstacles.size(); ++k) {
    const PlacedShape& obstacle = obstacles[k];
    if (!hasFeatures(obstacle.shape)) continue;
    const int K = static_cast<int>(k);
    // A mesh that the body's points touch is left to them: its triangles' ridges there are a
    // curved surface's facets or a finger's chamfers beside the pad, and faces held against
    // those as well let a squeezed block turn in the grip (rostest friction_grasp).
    if (obstacle.shape.kind == Shape::Kind::kMesh && pointsTouch(K)) continue;
    if (!placed) placePoints(body);
    placed = true;
    const Eigen::Isometry3d to_obstacle = obstacle.pose.inverse();
    if (obstacle.shape.kind == Shape::Kind::kMesh) {
      // Room for every triangle of the mesh, once: none is looked at twice for a face.
      const size_t triangles = obstacle.shape.mesh->mesh().triangles.size();
      if (near_triangles_.capacity() < triangles) near_triangles_.reserve(triangles);
    }
    separateFaces(body, obstacle, to_obstacle, K);
    const Eigen::AlignedBox3d near = boundsOf(obstacle, kOffItsFace);
    for (int t = 0; t < static_cast<int>(faces_.size()); ++t) {
      if (!face_pressed_[t] && !faceForFeatures(body, t, K, near)) continue;
      const TriangleSeparation s = separateFace(obstacle, to_obstacle, t);
      if (faceTouches(t, K, s.depth))
        touchFace(body, obstacles, start_poses, t, K, s.direction, dt);
      face_pressed_[t] = 0;
    }
    grantVelocities(body, K, dt);
  }
  // Held where they end: a later obstacle may have moved a face recorded for an earlier one.
  for (int i : face_nodes_) {
    face_place_[i] =
        obstacles[face_obstacle_[i]].pose.inverse() * body.positions().segment<3>(3 * i);
  }
  // The pushes of the last step's holds have been read.
  for (int i : face_held_) pushed_by_[i] = -1;
  face_held_.clear();
}

TriangleSeparation ContactState::separateFace(const PlacedShape& obstacle,
                                              const Eigen::Isometry3d& to_obstacle, int t) {
  const Eigen::Vector3d& a = point_x_[faces_[t][0]];
  const Eigen::Vector3d& b = point_x_[faces_[t][1]];
  const Eigen::Vector3d& c = point_x_[faces_[t][2]];
  if (obstacle.shape.kind == Shape::Kind::kBox)
    return separateFromBox(obstacle.pose, obstacle.shape.size, a, b, c);
  // A mesh dents the face along its own normal, inwards: the least way out of one of its
  // triangles is no way out of the solid they bound (through a bar's side, past its edge).
  const Eigen::Vector3d across = (c - a).cross(b - a);
  TriangleSeparation s;
  s.depth = -std::numeric_limits<double>::infinity();
  if (!(across.norm() > 0.0)) return s;  // a face crushed flat has no side to dent
  const Eigen::Vector3d inward = across.normalized();
  s.depth = obstacle.shape.mesh->dent(to_obstacle * a, to_obstacle * b, to_obstacle * c,
                                      to_obstacle.linear() * inward, kOffItsFace, near_triangles_);
  s.direction = inward;
  // Deeper than the face is wide, it is no dent of this face but a triangle reaching across it
  // (a table's top under a side face that hangs below it): the points answer there.
  const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  if (s.depth > longest) s.depth = -std::numeric_limits<double>::infinity();
  return s;
}

void ContactState::separateFaces(FiniteElementBody& body, const PlacedShape& obstacle,
                                 const Eigen::Isometry3d& to_obstacle, int k) {
  const Eigen::AlignedBox3d near = boundsOf(obstacle, 0.0);
  for (int pass = 0; pass < kEmbeddedPasses; ++pass) {
    for (int t = 0; t < static_cast<int>(faces_.size()); ++t) {
      if (!faceForFeatures(body, t, k, near)) continue;
      const TriangleSeparation s = separateFace(obstacle, to_obstacle, t);
      if (!(s.depth > kOnTheSurface)) continue;
      contacts_[k].penetration = std::max(contacts_[k].penetration, s.depth);
      face_pressed_[t] = 1;
      // The face moved whole, its free nodes alike (ContactState::request()).
      for (int corner = 0; corner < 3; ++corner) {
        request(body, faces_[t][corner], s.depth * s.direction, position_requests_);
      }
    }
    if (position_requests_.touched.empty()) return;
    grant(position_requests_, body.mutablePositions());
    placePoints(body);
  }
}

void ContactState::placePoints(const FiniteElementBody& body) {
  for (size_t p = 0; p < points_.size(); ++p) {
    point_x_[p] = weighted(body.positions(), static_cast<int>(p));
  }
}

bool ContactState::pointsTouch(int k) const {
  return std::find(obstacle_.begin(), obstacle_.end(), k) != obstacle_.end();
}

bool ContactState::faceForFeatures(const FiniteElementBody& body, int t, int k,
                                   const Eigen::AlignedBox3d& near) const {
  Eigen::AlignedBox3d bounds;
  for (int corner = 0; corner < 3; ++corner) {
    const int p = faces_[t][corner];
    if (obstacle_[p] == k) return false;
    bounds.extend(point_x_[p]);
  }
  if (!bounds.intersects(near)) return false;
  for (int corner = 0; corner < 3; ++corner) {
    if (!movable(body, faces_[t][corner])) return false;
  }
  return true;
}

bool ContactState::faceTouches(int t, int k, double depth) const {
  if (face_pressed_[t]) return true;
  if (!(depth > -kOffItsFace)) return false;
  // Held against the obstacle in the step: it touches on while its nodes' springs pushed in all.
  double push = 0.0;
  bool held = false;
  for (int corner = 0; corner < 3; ++corner) {
    const Point& point = points_[faces_[t][corner]];
    for (int j = 0; j < point.count; ++j) {
      const int i = point.nodes[j];
      if (pushed_by_[i] != k) continue;
      held = true;
      push += point.weights[j] * face_push_[i];
    }
  }
  return held && push > 0.0;
}

void ContactState::touchFace(const FiniteElementBody& body,
                             const std::vector<PlacedShape>& obstacles,
                             const std::vector<Eigen::Isometry3d>& start_poses, int t, int k,
                             const Eigen::Vector3d& direction, double dt) {
  face_touches_.push_back({t, k});
  const PlacedShape& obstacle = obstacles[k];
  const Eigen::Isometry3d to_obstacle = obstacle.pose.inverse();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero(), velocity = Eigen::Vector3d::Zero();
  for (int corner = 0; corner < 3; ++corner) {
    centre += point_x_[faces_[t][corner]] / 3.0;
    velocity += weighted(body.velocities(), faces_[t][corner]) / 3.0;
  }
  // Its way into the obstacle, relative to it (moving rigidly within the step), is stopped.
  const double into =
      -(velocity - obstacleVelocity(obstacle, start_poses[k], centre, dt)).dot(direction);
  for (int corner = 0; corner < 3; ++corner) {
    const int p = faces_[t][corner];
    if (into > 0.0) request(body, p, into * direction, velocity_requests_);
    const Point& point = points_[p];
    for (int j = 0; j < point.count; ++j) {
      const int i = point.nodes[j];
      if (point.weights[j] == 0.0 || body.isConstrained(i) || face_obstacle_[i] >= 0) continue;
      face_obstacle_[i] = k;
      face_normal_[i] = to_obstacle.linear() * direction;
      face_nodes_.push_back(i);
      // Held on, it goes on as judged. New, it has no judged force yet: a step on its plane gives
      // it a push to judge its friction by, as a landing point's impulse does.
      if (pushed_by_[i] == k && face_push_[i] > 0.0) continue;
      face_sticks_[i] = 0;
      face_friction_[i].setZero();
      face_excess_[i].setZero();
    }
  }
}

void ContactState::holdFaceNodes(FiniteElementBody& body,
                                 const std::vector<PlacedShape>& obstacles) {
  for (int i : face_nodes_) {
    if (body.isConstrained(i) || held_flag_[i] || on_plane_node_[i]) continue;
    const PlacedShape& obstacle = obstacles[face_obstacle_[i]];
    face_held_.push_back(i);
    if (face_sticks_[i]) {  // at its place on the obstacle, moving with it
      body.holdNodeAt(i, obstacle.pose * face_place_[i]);
      face_held_in_place_[i] = 1;
      continue;
    }
    body.holdNodeOnPlane(i, obstacle.pose.linear() * face_normal_[i],
                         obstacle.pose * face_place_[i]);
    const Eigen::Vector3d force = face_friction_[i] - face_excess_[i];
    if (!force.isZero(0.0)) body.addStepForce(i, force);
  }
}

void ContactState::addFaceNodesToPatches(const FiniteElementBody& body,
                                         const std::vector<PlacedShape>& obstacles) {
  for (int i : face_held_) {
    if (!face_held_in_place_[i]) continue;
    const int k = face_obstacle_[i];
    patches_[k].add(body.reactionForces().segment<3>(3 * i),
                    obstacles[k].pose.linear() * face_normal_[i], body.nodalMasses()[i]);
  }
}

void ContactState::judgeFaceNodes(const FiniteElementBody& body,
                                  const std::vector<PlacedShape>& obstacles,
                                  const std::vector<Eigen::Isometry3d>& start_poses,
                                  const ContactSettings& settings, double dt) {
  for (int i : face_held_) {
    const int k = face_obstacle_[i];
    const Eigen::Vector3d n = obstacles[k].pose.linear() * face_normal_[i];
    const Eigen::Vector3d r = body.reactionForces().segment<3>(3 * i);
    pushed_by_[i] = k;
    face_push_[i] = r.dot(n);
    if (!(face_push_[i] > 0.0)) continue;  // it pulled: let go
    if (!face_held_in_place_[i]) {
      judgeFaceNodeOnPlane(body, obstacles, start_poses, settings, dt, i);
      continue;
    }
    const Eigen::Vector3d x = body.positions().segment<3>(3 * i);
    const Patch& patch = patches_[k];
    if (!patch.slides) {
      addForce(k, x, r);
      continue;
    }
    // Its share of the patch's friction and of what the patch held beyond it, by its push (its
    // push is part of patch.pushing: addFaceNodesToPatches()); it slides on its plane from where
    // the step took it.
    const double share = face_push_[i] / patch.pushing;
    face_sticks_[i] = 0;
    face_friction_[i] = share * patch.friction;
    face_excess_[i] = share * (patch.sliding - patch.friction);
    addForce(k, x, face_push_[i] * n + face_friction_[i]);
  }
}

void ContactState::judgeFaceNodeOnPlane(const FiniteElementBody& body,
                                        const std::vector<PlacedShape>& obstacles,
                                        const std::vector<Eigen::Isometry3d>& start_poses,
                                        const ContactSettings& settings, double dt, int i) {
  const int k = face_obstacle_[i];
  const Eigen::Vector3d n = obstacles[k].pose.linear() * face_normal_[i];
  const Eigen::Vector3d x = body.positions().segment<3>(3 * i);
  addForce(k, x, face_push_[i] * n + face_friction_[i] - face_excess_[i]);
  face_excess_[i].setZero();
  const Eigen::Vector3d slip =
      slipOn(obstacles[k], start_poses[k], x, body.velocities().segment<3>(3 * i), n, dt);
  // At rest, it is held in place from the next step. Without friction it never sticks (points
  // at rest do: faces keep their frictionless holds).
  if (settings.friction > 0.0 && frictionStopped(face_friction_[i], slip)) {
    face_sticks_[i] = 1;
    face_friction_[i].setZero();
    return;
  }
  face_friction_[i] = slip.isZero(0.0)
                          ? Eigen::Vector3d::Zero()
                          : Eigen::Vector3d(-settings.friction * face_push_[i] * slip.normalized());
}

}  // namespace deformable_sim::core
