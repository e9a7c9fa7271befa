// Whether two triangles cross: the kernel of the self-intersection check
// (core/geometry/self_crossings.h).
#pragma once

#include <Eigen/Core>

namespace deformable_sim::core {

/// True when triangles (a0, a1, a2) and (b0, b1, b2) cross: a side of one passes strictly through
/// the inside of the other. Two triangles that are not in one plane cross exactly when this is so
/// (the segment they share ends on a side of one of them). Touching (a corner on the other
/// triangle, a side along it) and overlapping in one plane do not count. Allocates nothing.
bool trianglesCross(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& a2,
                    const Eigen::Vector3d& b0, const Eigen::Vector3d& b1,
                    const Eigen::Vector3d& b2);

}  // namespace deformable_sim::core
