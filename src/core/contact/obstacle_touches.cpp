#include "deformable_sim/core/contact/obstacle_touches.h"

namespace deformable_sim::core {

namespace {

/// Half the extent of the shape's own bounding box, and its centre, in its frame.
Eigen::AlignedBox3d localBounds(const Shape& shape) {
  Eigen::Vector3d half = Eigen::Vector3d::Zero();
  switch (shape.kind) {
    case Shape::Kind::kBox:
      half = 0.5 * shape.size;
      break;
    case Shape::Kind::kSphere:
      half.setConstant(shape.radius);
      break;
    case Shape::Kind::kCylinder:
      half = Eigen::Vector3d(shape.radius, shape.radius, 0.5 * shape.length);
      break;
    case Shape::Kind::kMesh:
      return shape.mesh->bounds();
  }
  return Eigen::AlignedBox3d(-half, half);
}

}  // namespace

Eigen::AlignedBox3d worldBounds(const PlacedShape& obstacle, double margin) {
  const Eigen::AlignedBox3d local = localBounds(obstacle.shape);
  const Eigen::Vector3d centre = obstacle.pose * local.center();
  const Eigen::Vector3d half =
      obstacle.pose.linear().cwiseAbs() * (0.5 * local.sizes()) + Eigen::Vector3d::Constant(margin);
  return Eigen::AlignedBox3d(centre - half, centre + half);
}

Eigen::Vector3d obstacleVelocity(const PlacedShape& obstacle, const Eigen::Isometry3d& start_pose,
                                 const Eigen::Vector3d& x, double dt) {
  return (x - start_pose * (obstacle.pose.inverse() * x)) / dt;
}

void findObstacleTouches(int body, const std::vector<int>& corners,
                         const std::vector<Eigen::Vector3d>& positions,
                         const std::vector<PlacedShape>& obstacles,
                         const std::vector<Eigen::Isometry3d>& start_poses, double dt,
                         double margin, std::vector<ObstacleTouch>& touches) {
  if (corners.empty()) return;
  Eigen::AlignedBox3d body_box;
  for (int c : corners) body_box.extend(positions[c]);
  for (size_t k = 0; k < obstacles.size(); ++k) {
    const PlacedShape& obstacle = obstacles[k];
    const Eigen::AlignedBox3d near = worldBounds(obstacle, margin);
    if (!near.intersects(body_box)) continue;
    const Eigen::Isometry3d to_shape = obstacle.pose.inverse();
    for (int c : corners) {
      const Eigen::Vector3d& x = positions[c];
      if (!near.contains(x)) continue;
      Eigen::Vector3d surface, normal;
      const double gap = signedDistance(obstacle.shape, to_shape * x, &surface, &normal);
      if (!(gap < margin)) continue;
      ObstacleTouch touch;
      touch.body = body;
      touch.corner = c;
      touch.obstacle = static_cast<int>(k);
      touch.position = x;
      touch.normal = (obstacle.pose.linear() * normal).normalized();
      touch.gap = gap;
      touch.obstacle_velocity = obstacleVelocity(obstacle, start_poses[k], x, dt);
      touches.push_back(touch);
    }
  }
}

}  // namespace deformable_sim::core
