// A structured tetrahedral mesh of a box, for built-in scenes, tests and benchmarks.
#pragma once

#include <Eigen/Core>

#include "deformable_sim/core/mesh.h"

namespace deformable_sim::core {

/// The box [min, max] cut into cells[0] x cells[1] x cells[2] cubes, each split into six
/// tetrahedra around a main diagonal, mirrored from cell to cell (a conforming split with the
/// box's mirror symmetries).
/// Node numbers run from 1 in x-fastest order. Throws std::invalid_argument for an empty box or
/// fewer than one cell per axis.
Mesh makeBoxMesh(const Eigen::Vector3d& min, const Eigen::Vector3d& max,
                 const Eigen::Vector3i& cells);

}  // namespace deformable_sim::core
