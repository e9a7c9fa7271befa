// Rotation of an element from its deformation gradient.
#pragma once

#include <Eigen/Core>

namespace deformable_sim::core {

/// The rotation R of the polar decomposition F = R S, always a proper rotation (det R = +1),
/// also for flat (rank-deficient) and inverted (det F < 0) elements.
///
/// From the SVD F = U Sigma V^T, R = U V^T. When det(U V^T) = -1 the reflection is moved into
/// the direction of the smallest singular value (Irving, Teran, Fedkiw 2004, "Invertible finite
/// elements"), which is the rotation closest to F among proper rotations.
Eigen::Matrix3d extractRotation(const Eigen::Matrix3d& deformation_gradient);

}  // namespace deformable_sim::core
