// Poses interpolated between two, as grasps follow their frames.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "deformable_sim/core/driver/pose_interpolation.h"

namespace deformable_sim::core {
namespace {

TEST(PoseInterpolation, RunsFromOnePoseToTheOther) {
  Eigen::Isometry3d from = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d to = Eigen::Isometry3d::Identity();
  to.translate(Eigen::Vector3d(1.0, 2.0, 3.0));
  to.rotate(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  EXPECT_TRUE(interpolatePose(from, to, 0.0).isApprox(from, 1e-12));
  EXPECT_TRUE(interpolatePose(from, to, 1.0).isApprox(to, 1e-12));
  const Eigen::Isometry3d half = interpolatePose(from, to, 0.5);
  EXPECT_TRUE(half.translation().isApprox(Eigen::Vector3d(0.5, 1.0, 1.5), 1e-12));
  EXPECT_NEAR(Eigen::AngleAxisd(half.linear()).angle(), M_PI / 4, 1e-12);
}

}  // namespace
}  // namespace deformable_sim::core
