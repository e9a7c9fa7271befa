// Grasps that follow frames a driver tracks (tf in the node): which frame each grasp follows, and
// its moves over a tick's substeps, evenly from where the frame was to where it is now.
#pragma once

#include <Eigen/Geometry>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "deformable_sim/core/session/session.h"

namespace deformable_sim::core {

class GraspFollower {
 public:
  /// The pose of a frame now, or nullopt when it is not known.
  using FramePose = std::function<std::optional<Eigen::Isometry3d>(const std::string& frame)>;

  void follow(const std::string& grasp, const std::string& frame) { frames_[grasp] = frame; }
  void forget(const std::string& grasp) {
    frames_.erase(grasp);
    moves_.erase(grasp);
  }
  void clear() {
    frames_.clear();
    moves_.clear();
  }
  /// Grasp -> the frame it follows.
  const std::map<std::string, std::string>& frames() const { return frames_; }

  /// Plans each grasp's move from its pose now to `pose(frame)`; a frame without a pose holds
  /// its grasp where it is. Returns the grasps whose frames had none.
  std::vector<std::string> plan(const CommandProcessor& commands, const FramePose& pose);
  /// The moves after substep `s` of `steps` (1 <= s <= steps): exactly the target at the last.
  /// Valid until the next call.
  const std::vector<MoveGraspCommand>& moves(int s, int steps);

 private:
  std::map<std::string, std::string> frames_;
  std::map<std::string, std::pair<Eigen::Isometry3d, Eigen::Isometry3d>> moves_;  ///< from, to
  std::vector<MoveGraspCommand> substep_;  ///< the moves of one substep, reused
};

}  // namespace deformable_sim::core
