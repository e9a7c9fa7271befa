// A structured mesh of a box, for built-in scenes, tests and benchmarks.
#pragma once

#include <Eigen/Core>

#include "deformable_sim/core/elements/mesh.h"

namespace deformable_sim::core {

enum class BoxElement { kTetrahedron, kHexahedron, kWedge, kPyramid };

/// The most cells a box mesh may have: far beyond real time already, and a bound on what a scene
/// file can make the reader allocate (a few GB of stiffness at most).
constexpr long kMaxBoxMeshCells = 1000000;

/// The box [min, max] cut into cells[0] x cells[1] x cells[2] cubes, each one hexahedron, or
/// split into six tetrahedra around a main diagonal, mirrored from cell to cell (a conforming
/// split, with the box's mirror symmetries where the cells along an axis are even in number), two
/// wedges, or six pyramids around a node added at its centre. Node numbers run from 1 in x-fastest
/// order (cube centres last). Throws std::invalid_argument for an empty box, fewer than one cell
/// per axis or more than kMaxBoxMeshCells cells.
Mesh makeBoxMesh(const Eigen::Vector3d& min, const Eigen::Vector3d& max,
                 const Eigen::Vector3i& cells, BoxElement element = BoxElement::kTetrahedron);

}  // namespace deformable_sim::core
