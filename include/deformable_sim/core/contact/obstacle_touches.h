// Detection, the first part of a step's contact (core/contact/contact_impulses.h): which points of
// a body's collision surface are inside an obstacle, or near enough that the step's answer to the
// other contacts may bring them in, at the end of the bodies' free step, with what the contact
// problem needs of each: the obstacle's normal there, the gap, and the obstacle's own velocity.
#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "deformable_sim/core/geometry/shape.h"

namespace deformable_sim::core {

/// A point of a body at or near an obstacle after the body's free step.
struct ObstacleTouch {
  int body = 0;
  int corner = 0;  ///< the point: a corner of the body's collision surface (core/body_surface.h)
  int obstacle = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< the point, world, m
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();   ///< out of the obstacle there, world
  double gap = 0.0;  ///< signed distance to the obstacle's surface, m (negative: inside)
  /// The velocity of the obstacle's point at `position`, moving rigidly from its pose at the step's
  /// start to its pose at the end, m/s.
  Eigen::Vector3d obstacle_velocity = Eigen::Vector3d::Zero();
};

/// The world box that holds `obstacle`, widened by `margin` (m).
Eigen::AlignedBox3d worldBounds(const PlacedShape& obstacle, double margin);

/// The velocity at world point x of an obstacle that moved rigidly from `start_pose` to its pose
/// in a step of dt s: where x is now, less where the same point of the obstacle was, over dt.
Eigen::Vector3d obstacleVelocity(const PlacedShape& obstacle, const Eigen::Isometry3d& start_pose,
                                 const Eigen::Vector3d& x, double dt);

/// Appends to `touches` the `corners` of body `body` (at `positions`, indexed by corner, world)
/// that are within `margin` (m) of an obstacle, once per obstacle each is near, by obstacle and
/// then corner. `start_poses[k]`: obstacle k's pose at the step's start.
/// Allocates only when `touches` outgrows its reserve.
void findObstacleTouches(int body, const std::vector<int>& corners,
                         const std::vector<Eigen::Vector3d>& positions,
                         const std::vector<PlacedShape>& obstacles,
                         const std::vector<Eigen::Isometry3d>& start_poses, double dt,
                         double margin, std::vector<ObstacleTouch>& touches);

}  // namespace deformable_sim::core
