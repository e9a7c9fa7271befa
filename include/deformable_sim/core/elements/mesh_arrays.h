// A mesh as flat arrays, the way a message or a file carries it, and back. Reading back checks
// everything a recorded or received mesh could get wrong.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "deformable_sim/core/elements/mesh.h"

namespace deformable_sim::core {

struct MeshArrays {
  std::vector<int64_t> node_numbers;   ///< the mesh file's number of each node
  std::vector<double> rest_positions;  ///< m, x y z per node
  std::vector<uint32_t> tetrahedra;    ///< 4 node indices per tetrahedron
  std::vector<uint8_t> cell_types;     ///< per other element: its node count (5, 6 or 8)
  std::vector<uint32_t> cells;         ///< their node indices, cell_types[k] of them per cell
  /// Mesh::cell_fractions: 8 per cell (its octants), or empty for full cells.
  std::vector<double> cell_fractions;
  bool incompatible_modes = false;  ///< Mesh::incompatible_modes
};

MeshArrays toArrays(const Mesh& mesh);

/// Throws std::invalid_argument, naming `what` (e.g. "the mesh of body 'beam'"), when the arrays'
/// sizes do not fit, an index is out of range or a cell type is unknown.
Mesh fromArrays(const MeshArrays& arrays, const std::string& what);

}  // namespace deformable_sim::core
