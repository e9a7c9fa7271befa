// A pose part of the way from one pose to another: how a grasp's frame moves over the substeps
// of a tick, from where it was to where tf has it now.
#pragma once

#include <Eigen/Geometry>

namespace deformable_sim::core {

/// Linear in the translation, spherical-linear in the rotation; t = 0 gives `from`, t = 1 `to`.
inline Eigen::Isometry3d interpolatePose(const Eigen::Isometry3d& from, const Eigen::Isometry3d& to,
                                         double t) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = (1.0 - t) * from.translation() + t * to.translation();
  pose.linear() = Eigen::Quaterniond(from.linear())
                      .slerp(t, Eigen::Quaterniond(to.linear()))
                      .toRotationMatrix();
  return pose;
}

}  // namespace deformable_sim::core
