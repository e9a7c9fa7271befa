#include "deformable_sim/core/rotation.h"

#include <Eigen/LU>
#include <Eigen/SVD>

namespace deformable_sim::core {

Eigen::Matrix3d extractRotation(const Eigen::Matrix3d& deformation_gradient) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(deformation_gradient,
                                              Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d u = svd.matrixU();
  const Eigen::Matrix3d& v = svd.matrixV();
  // JacobiSVD sorts singular values in decreasing order: column 2 is the smallest.
  if ((u * v.transpose()).determinant() < 0.0) u.col(2) = -u.col(2);
  return u * v.transpose();
}

}  // namespace deformable_sim::core
