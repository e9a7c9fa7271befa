// A URDF origin (urdfdom's pose) as an Eigen transform: for the readers of collision shapes and
// of visual meshes.
#pragma once

#include <urdf_model/pose.h>

#include <Eigen/Geometry>

namespace deformable_sim::io {

inline Eigen::Isometry3d toIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d result = Eigen::Isometry3d::Identity();
  result.translation() << pose.position.x, pose.position.y, pose.position.z;
  result.linear() =
      Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
          .normalized()
          .toRotationMatrix();
  return result;
}

}  // namespace deformable_sim::io
