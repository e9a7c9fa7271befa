// A scene's obstacles: its own fixed ones, and shapes attached to frames that move (a robot's
// links, posed by tf in the node), placed anew each tick.
#pragma once

#include <Eigen/Geometry>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "deformable_sim/core/geometry/shape.h"

namespace deformable_sim::core {

class LinkedObstacles {
 public:
  /// The pose of a frame in the world now, or nullopt when it is not known.
  using FramePose = std::function<std::optional<Eigen::Isometry3d>(const std::string& frame)>;

  explicit LinkedObstacles(std::vector<PlacedShape> fixed) : fixed_(std::move(fixed)) {}

  /// A shape posed in `frame`'s coordinates.
  void attach(const std::string& frame, const PlacedShape& local) {
    attached_.push_back({frame, local, std::nullopt});
  }
  /// Every obstacle in the world: the fixed ones, then the attached ones in the order attached.
  /// A frame without a pose now keeps its shapes where they were; nullopt while some frame has
  /// never had one (a body must not fall through an obstacle not yet placed).
  std::optional<std::vector<PlacedShape>> place(const FramePose& pose);

 private:
  struct Attached {
    std::string frame;
    PlacedShape local;                  ///< pose in the frame
    std::optional<PlacedShape> placed;  ///< in the world, once the frame had a pose
  };
  std::vector<PlacedShape> fixed_;
  std::vector<Attached> attached_;
};

}  // namespace deformable_sim::core
