// The best-fit rigid frame of a set of nodes (shape matching, Müller et al. 2005): what a body or a
// node group does "as a whole", published as its tf frame.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace deformable_sim::core {

/// Maps rest coordinates to current ones: x ≈ origin + rotation (x0 − rest_origin).
struct RigidFrame {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();        ///< current mass centroid c, m
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  ///< proper rotation
  Eigen::Vector3d rest_origin = Eigen::Vector3d::Zero();   ///< rest mass centroid c0, m
};

/// The frame as a pose in the world: origin at the current centroid.
inline Eigen::Isometry3d toIsometry(const RigidFrame& frame) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = frame.origin;
  pose.linear() = frame.rotation;
  return pose;
}

/// Best-fit frame of the nodes `nodes` (all nodes when empty) of stacked 3n positions x, rest
/// positions x0 and masses m: c = Σ m x / Σ m, rotation = polar rotation of
/// A = Σ m (x − c)(x0 − c0)ᵀ. At rest the rotation is the identity.
RigidFrame bestFitFrame(const Eigen::VectorXd& x, const Eigen::VectorXd& x0,
                        const std::vector<double>& masses, const std::vector<int>& nodes = {});

}  // namespace deformable_sim::core
