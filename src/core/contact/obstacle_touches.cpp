#include "deformable_sim/core/contact/obstacle_touches.h"

namespace deformable_sim::core {

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

}  // namespace deformable_sim::core
