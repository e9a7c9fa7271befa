#include "deformable_sim/core/driver/grasp_follower.h"

#include "deformable_sim/core/driver/pose_interpolation.h"

namespace deformable_sim::core {

std::vector<std::string> GraspFollower::plan(const CommandProcessor& commands,
                                             const FramePose& pose) {
  std::vector<std::string> lost;
  moves_.clear();
  for (const auto& [grasp, frame] : frames_) {
    const Eigen::Isometry3d from = commands.grasps().at(grasp).frame;
    std::optional<Eigen::Isometry3d> to = pose(frame);
    if (!to) {
      lost.push_back(grasp);
      to = from;
    }
    moves_.emplace(grasp, std::make_pair(from, *to));
  }
  return lost;
}

const std::vector<MoveGraspCommand>& GraspFollower::moves(int s, int steps) {
  substep_.resize(moves_.size());
  size_t k = 0;
  for (const auto& [grasp, poses] : moves_) {
    const auto& [from, to] = poses;
    substep_[k].name = grasp;  // same length as last time: no allocation
    substep_[k++].frame = s == steps ? to : interpolatePose(from, to, double(s) / steps);
  }
  return substep_;
}

}  // namespace deformable_sim::core
