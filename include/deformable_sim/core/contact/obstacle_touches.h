// Detection, the first part of a step's contact (core/contact/contact_impulses.h): which points of
// a body's collision surface may meet an obstacle within the step. Each point is looked at where
// it was at the step's start, against the obstacle where it was then: its gap there, the
// obstacle's normal, and the obstacle's velocity, so that the problem can keep the gap at the
// step's end, gap + dt (v - u) . n, from closing past zero. A point that crossed a thin obstacle
// within the free step is still stopped at the face it came to, and a point looked at from where
// it started is never taken through to an obstacle's far side.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "deformable_sim/core/contact/body_surface.h"
#include "deformable_sim/core/geometry/shape.h"

namespace deformable_sim::core {

/// A point of a body that may meet an obstacle within the step.
struct ObstacleTouch {
  int body = 0;
  /// The point: a corner of the body's collision surface (core/contact/body_surface.h), or, where
  /// an obstacle's edge or corner meets one of its triangles between corners, the point of
  /// triangle `face` with barycentric `weights` (corner -1).
  int corner = -1;
  int face = -1;
  std::array<double, 3> weights{};
  int obstacle = 0;
  /// Out of the obstacle at the point's start, in the world at the step's end (it turns with the
  /// obstacle).
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  /// The signed distance from the point to the obstacle's surface at the step's start, m
  /// (negative: inside).
  double gap = 0.0;
  /// The velocity of the obstacle's point where the point started, moving rigidly from its pose
  /// at the step's start to its pose at the end, m/s.
  Eigen::Vector3d obstacle_velocity = Eigen::Vector3d::Zero();
};

/// The world box that holds `shape` at `pose`, widened by `margin` (m).
Eigen::AlignedBox3d worldBounds(const Shape& shape, const Eigen::Isometry3d& pose, double margin);

/// The velocity of the point of an obstacle at world point x at the step's start, the obstacle
/// moving rigidly from `start_pose` to its pose in a step of dt s: where that point is at the
/// step's end, less x, over dt.
Eigen::Vector3d obstacleVelocity(const PlacedShape& obstacle, const Eigen::Isometry3d& start_pose,
                                 const Eigen::Vector3d& x, double dt);

/// Appends to `touches` the `corners` of body `body` that may meet an obstacle within a step of dt:
/// those whose gap at the step's start (`starts`, indexed by corner, world) is within `margin`
/// (m) plus the way their free velocities (`velocities`, likewise) take them towards it in the
/// step. Once per obstacle each is near, by obstacle and then corner. `start_poses[k]`: obstacle
/// k's pose at the step's start. Allocates only when `touches` outgrows its reserve.
void findObstacleTouches(int body, const std::vector<int>& corners,
                         const std::vector<Eigen::Vector3d>& starts,
                         const std::vector<Eigen::Vector3d>& velocities,
                         const std::vector<PlacedShape>& obstacles,
                         const std::vector<Eigen::Isometry3d>& start_poses, double dt,
                         double margin, std::vector<ObstacleTouch>& touches);

/// Appends to `touches` the points where the edges of box and mesh obstacles (a mesh's ridges:
/// TriangleMeshShape::ridge) may dent body `body`'s `faces` (triangles of corners) between their
/// corners within a step of dt: per face and obstacle, the deepest dent of its edges into the
/// face along the face's inward normal, within the face's outline
/// (core/geometry/triangle_separation.h edgeDent), if its gap is within `margin` plus the way
/// the face goes towards it. The normal is the face's, inward. Left out: a dent at one of the
/// face's corners (that corner's own), and one within `margin` of a fold of the body's surface
/// at the face's side (a finger squeezing a cube reaches below it: its lower edge is in front
/// of the cube's bottom faces, but along the side it presses, not under them). `starts`,
/// `velocities`: per corner; `near` is room for a mesh's triangles.
void findFaceTouches(int body, const BodySurface& surface,
                     const std::vector<Eigen::Vector3d>& starts,
                     const std::vector<Eigen::Vector3d>& velocities,
                     const std::vector<PlacedShape>& obstacles,
                     const std::vector<Eigen::Isometry3d>& start_poses, double dt, double margin,
                     std::vector<int>& near, std::vector<ObstacleTouch>& touches);

}  // namespace deformable_sim::core
