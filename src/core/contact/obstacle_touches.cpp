#include "deformable_sim/core/contact/obstacle_touches.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "deformable_sim/core/geometry/triangle_mesh_shape.h"
#include "deformable_sim/core/geometry/triangle_separation.h"

namespace deformable_sim::core {

namespace {

/// sin 15 degrees: an obstacle's edge steeper than this to a face goes through it, not along it.
constexpr double kAlongFace = 0.26;
/// cos 10 degrees: an obstacle's side turned this near to a body's face lies flat on it.
constexpr double kFlatCosine = 0.985;
/// sin 10 degrees: an obstacle's side turned this far away from a body's face is behind its
/// edge, seen from the face.
constexpr double kBehindSine = 0.175;

/// Whether the edge where an obstacle's sides of outward unit normals `first` and `second` meet
/// can press into the face of inward unit normal `inward`: only when both sides face the body,
/// the obstacle then lying in front of the face (a finger's lower edge reaching below a cube it
/// squeezes is in front of the cube's bottom faces, but its underside turns away from them: it
/// is at the side it presses, not under the cube), and neither lies flat on the face (its edges
/// then bound a patch pressed flat, carried by the body's corners within it where the patch is
/// wider than the face, by the obstacle's corners where it is narrower: pressing the edges too
/// would ask the same twice).
bool pressesInto(const Eigen::Vector3d& first, const Eigen::Vector3d& second,
                 const Eigen::Vector3d& inward) {
  const double a = first.dot(inward), b = second.dot(inward);
  return a > -kBehindSine && b > -kBehindSine && a < kFlatCosine && b < kFlatCosine;
}

/// Keeps in `dent` the deeper of it and the obstacle's edge p, q into the face a, b, c of unit
/// normal `inward`. Two kinds of edges are no dent of the face: one that goes through it, deepest
/// where the outline cuts it (a bar pressed across a cube's top, where it passes its side faces:
/// pushing those faces along their normals cannot take them off it; the top faces answer), and
/// one reaching deeper than the face is wide (a table's edge under a side face hanging past it:
/// the corners answer).
void deepen(EdgeDent& dent, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
            const Eigen::Vector3d& c, const Eigen::Vector3d& inward, double longest,
            const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
  const EdgeDent edge = edgeDent(a, b, c, inward, p, q);
  if (!edge.at_corner && std::abs(inward.dot(q - p)) > kAlongFace * (q - p).norm()) return;
  if (edge.depth > dent.depth && edge.depth <= longest) dent = edge;
}

/// The deepest dent of a box's or a mesh's ridges into the face a, b, c (the obstacle's frame).
EdgeDent dentOf(const Shape& shape, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                const Eigen::Vector3d& c, const Eigen::Vector3d& inward, double margin,
                std::vector<int>& near) {
  const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  EdgeDent dent;
  if (shape.kind == Shape::Kind::kBox) {
    // Its twelve edges: from each corner with a coordinate at its lower bound, along that axis.
    const Eigen::Vector3d h = 0.5 * shape.size;
    for (int i = 0; i < 8; ++i) {
      const Eigen::Vector3d corner(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(),
                                   i & 4 ? h.z() : -h.z());
      for (int axis = 0; axis < 3; ++axis) {
        if (i & (1 << axis)) continue;
        // The two sides that meet at this edge.
        const int first = (axis + 1) % 3, second = (axis + 2) % 3;
        const double first_side = i & (1 << first) ? 1.0 : -1.0;
        const double second_side = i & (1 << second) ? 1.0 : -1.0;
        if (!pressesInto(first_side * Eigen::Vector3d::Unit(first),
                         second_side * Eigen::Vector3d::Unit(second), inward)) {
          continue;
        }
        Eigen::Vector3d other = corner;
        other[axis] = h[axis];
        deepen(dent, a, b, c, inward, longest, corner, other);
      }
    }
    return dent;
  }
  const TriangleMeshShape& mesh = *shape.mesh;
  const Eigen::Vector3d reach = Eigen::Vector3d::Constant(margin);
  near.clear();
  mesh.trianglesNear(a.cwiseMin(b).cwiseMin(c) - reach, a.cwiseMax(b).cwiseMax(c) + reach, near);
  for (int t : near) {
    const Eigen::Vector3i& v = mesh.mesh().triangles[t];
    for (int k = 0; k < 3; ++k) {
      if (!mesh.ridge(t, k)) continue;
      const int other = mesh.across(t, k);  // a free edge has one side only
      const Eigen::Vector3d& side = mesh.faceNormal(t);
      if (!pressesInto(side, other >= 0 ? mesh.faceNormal(other) : side, inward)) continue;
      deepen(dent, a, b, c, inward, longest, mesh.mesh().vertices[v[k]],
             mesh.mesh().vertices[v[(k + 1) % 3]]);
    }
  }
  return dent;
}

/// Barycentric weights of `p` (on the plane of a, b, c) in that triangle, put inside it.
std::array<double, 3> weightsIn(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double area = n.squaredNorm();
  std::array<double, 3> w{(b - p).cross(c - p).dot(n) / area, (c - p).cross(a - p).dot(n) / area,
                          0.0};
  w[0] = std::clamp(w[0], 0.0, 1.0);
  w[1] = std::clamp(w[1], 0.0, 1.0 - w[0]);
  w[2] = 1.0 - w[0] - w[1];
  return w;
}

/// Whether the point of face t with `weights` (corners `corners`) is within `margin` of one of
/// the face's folds (BodySurface::fold): an obstacle's edge along a fold of the body (a finger's
/// side along a squeezed cube's edge) meets the fold, which the corners along it answer.
bool nearAFold(const BodySurface& surface, int t, const std::array<double, 3>& weights,
               const std::array<Eigen::Vector3d, 3>& corners, double margin) {
  const double twice_area = (corners[1] - corners[0]).cross(corners[2] - corners[0]).norm();
  for (int k = 0; k < 3; ++k) {
    if (!surface.fold(t, k)) continue;
    // From the side k, k + 1: the opposite corner's weight times its height over that side.
    const double side = (corners[(k + 1) % 3] - corners[k]).norm();
    if (weights[(k + 2) % 3] * twice_area / side < margin) return true;
  }
  return false;
}

}  // namespace

Eigen::AlignedBox3d worldBounds(const Shape& shape, const Eigen::Isometry3d& pose, double margin) {
  const Eigen::AlignedBox3d local = bounds(shape);
  const Eigen::Vector3d centre = pose * local.center();
  const Eigen::Vector3d half =
      pose.linear().cwiseAbs() * (0.5 * local.sizes()) + Eigen::Vector3d::Constant(margin);
  return Eigen::AlignedBox3d(centre - half, centre + half);
}

Eigen::Vector3d obstacleVelocity(const PlacedShape& obstacle, const Eigen::Isometry3d& start_pose,
                                 const Eigen::Vector3d& x, double dt) {
  return (obstacle.pose * (start_pose.inverse() * x) - x) / dt;
}

void findObstacleTouches(int body, const std::vector<int>& corners,
                         const std::vector<Eigen::Vector3d>& starts,
                         const std::vector<Eigen::Vector3d>& velocities,
                         const std::vector<PlacedShape>& obstacles,
                         const std::vector<Eigen::Isometry3d>& start_poses, double dt,
                         double margin, std::vector<ObstacleTouch>& touches) {
  if (corners.empty()) return;
  Eigen::AlignedBox3d body_box;  // where the corners go in the step, widened below by the margin
  for (int c : corners) {
    body_box.extend(starts[c]);
    body_box.extend(starts[c] + dt * velocities[c]);
  }
  for (size_t k = 0; k < obstacles.size(); ++k) {
    const PlacedShape& obstacle = obstacles[k];
    const Eigen::AlignedBox3d near_then = worldBounds(obstacle.shape, start_poses[k], margin);
    const Eigen::AlignedBox3d near_now = worldBounds(obstacle.shape, obstacle.pose, margin);
    if (!near_then.intersects(body_box) && !near_now.intersects(body_box)) continue;
    const Eigen::Isometry3d to_start_shape = start_poses[k].inverse();
    for (int c : corners) {
      const Eigen::Vector3d& x = starts[c];
      const Eigen::Vector3d u = obstacleVelocity(obstacle, start_poses[k], x, dt);
      const double reach = dt * (velocities[c] - u).norm();
      // The gap is at least the way to the box around the obstacle: far corners cost no more.
      if (near_then.exteriorDistance(x) > reach) continue;
      Eigen::Vector3d surface, normal;
      const double gap = signedDistance(obstacle.shape, to_start_shape * x, &surface, &normal);
      if (!(gap < margin + reach)) continue;
      ObstacleTouch touch;
      touch.body = body;
      touch.corner = c;
      touch.obstacle = static_cast<int>(k);
      touch.normal = (obstacle.pose.linear() * normal).normalized();
      touch.gap = gap;
      touch.obstacle_velocity = u;
      touches.push_back(touch);
    }
  }
}

void findFaceTouches(int body, const BodySurface& surface,
                     const std::vector<Eigen::Vector3d>& starts,
                     const std::vector<Eigen::Vector3d>& velocities,
                     const std::vector<PlacedShape>& obstacles,
                     const std::vector<Eigen::Isometry3d>& start_poses, double dt, double margin,
                     std::vector<int>& near, std::vector<ObstacleTouch>& touches) {
  for (size_t k = 0; k < obstacles.size(); ++k) {
    const PlacedShape& obstacle = obstacles[k];
    if (obstacle.shape.kind != Shape::Kind::kBox && obstacle.shape.kind != Shape::Kind::kMesh) {
      continue;
    }
    const Eigen::AlignedBox3d near_then = worldBounds(obstacle.shape, start_poses[k], margin);
    const Eigen::Isometry3d to_start_shape = start_poses[k].inverse();
    for (int t = 0; t < static_cast<int>(surface.triangles().size()); ++t) {
      const Triangle& face = surface.triangles()[t];
      Eigen::AlignedBox3d swept;
      for (int corner : face) {
        swept.extend(starts[corner]);
        swept.extend(starts[corner] + dt * velocities[corner]);
      }
      if (!swept.intersects(near_then)) continue;
      const Eigen::Vector3d a = to_start_shape * starts[face[0]];
      const Eigen::Vector3d b = to_start_shape * starts[face[1]];
      const Eigen::Vector3d c = to_start_shape * starts[face[2]];
      const Eigen::Vector3d across = (c - a).cross(b - a);
      if (!(across.norm() > 0.0)) continue;  // a face crushed flat has no side to dent
      const Eigen::Vector3d inward = across.normalized();
      const EdgeDent dent = dentOf(obstacle.shape, a, b, c, inward, margin, near);
      if (!std::isfinite(dent.depth)) continue;  // no edge within its outline
      ObstacleTouch touch;
      touch.weights = weightsIn(dent.at - dent.depth * inward, a, b, c);
      // Within the margin of a corner, it is that corner's touch.
      const Eigen::Vector3d on_face =
          touch.weights[0] * a + touch.weights[1] * b + touch.weights[2] * c;
      if ((on_face - a).norm() < margin || (on_face - b).norm() < margin ||
          (on_face - c).norm() < margin) {
        continue;
      }
      if (nearAFold(surface, t, touch.weights, {a, b, c}, margin)) continue;
      Eigen::Vector3d x = Eigen::Vector3d::Zero(), v = Eigen::Vector3d::Zero();
      for (int i = 0; i < 3; ++i) {
        x += touch.weights[i] * starts[face[i]];
        v += touch.weights[i] * velocities[face[i]];
      }
      const Eigen::Vector3d u = obstacleVelocity(obstacle, start_poses[k], x, dt);
      if (!(-dent.depth < margin + dt * (v - u).norm())) continue;
      touch.body = body;
      touch.face = t;
      touch.obstacle = static_cast<int>(k);
      touch.normal = obstacle.pose.linear() * inward;
      touch.gap = -dent.depth;
      touch.obstacle_velocity = u;
      touches.push_back(touch);
    }
  }
}

}  // namespace deformable_sim::core
