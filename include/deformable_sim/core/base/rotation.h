// Rotation of an element from its deformation gradient.
#pragma once

#include <Eigen/Core>

namespace deformable_sim::core {

/// The rotation R of the polar decomposition F = R S, always a proper rotation (det R = +1),
/// also for flat (rank-deficient) and inverted (det F < 0) elements.
///
/// Elements in their normal range (det F well above zero) take, near a rotation, the
/// Newton-Schulz iteration X <- X (3 I - X^T X) / 2 (products only), and otherwise Higham's
/// scaled Newton iteration X <- (g X + X^-T / g) / 2; both converge quadratically to R from
/// X = F with nothing but 3x3 products and cofactors: several times cheaper than an SVD. Flat,
/// nearly flat and inverted elements take the SVD F = U Sigma V^T, R = U V^T, with the reflection
/// of det(U V^T) = -1 moved into the direction of the smallest singular value (Irving, Teran,
/// Fedkiw 2004, "Invertible finite elements"), which gives the proper rotation closest to F. Both
/// agree to rounding where both apply.
Eigen::Matrix3d extractRotation(const Eigen::Matrix3d& deformation_gradient);

/// How many rotations extractRotations takes at once.
constexpr int kRotationBatch = 4;

/// extractRotation for `count` (at most kRotationBatch) deformation gradients at once, in
/// lockstep where they are near rotations (the common case, vectorized across them). Each
/// result agrees with extractRotation's to rounding.
void extractRotations(const Eigen::Matrix3d* deformation_gradients, Eigen::Matrix3d* rotations,
                      int count);

/// The SVD route of extractRotation for every F (for tests and comparisons).
Eigen::Matrix3d extractRotationBySvd(const Eigen::Matrix3d& deformation_gradient);

/// [d]x, the matrix of d x (.): the rate of a rotation about d.
inline Eigen::Matrix3d crossMatrix(const Eigen::Vector3d& d) {
  Eigen::Matrix3d c;
  c << 0.0, -d.z(), d.y(), d.z(), 0.0, -d.x(), -d.y(), d.x(), 0.0;
  return c;
}

}  // namespace deformable_sim::core
