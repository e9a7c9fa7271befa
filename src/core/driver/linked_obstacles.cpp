#include "deformable_sim/core/driver/linked_obstacles.h"

namespace deformable_sim::core {

std::optional<std::vector<PlacedShape>> LinkedObstacles::place(const FramePose& pose) {
  std::vector<PlacedShape> obstacles = fixed_;
  bool complete = true;
  for (Attached& shape : attached_) {
    if (const std::optional<Eigen::Isometry3d> frame = pose(shape.frame)) {
      shape.placed = shape.local;
      shape.placed->pose = *frame * shape.local.pose;
    }
    if (shape.placed) {
      obstacles.push_back(*shape.placed);
    } else {
      complete = false;
    }
  }
  if (!complete) return std::nullopt;
  return obstacles;
}

}  // namespace deformable_sim::core
