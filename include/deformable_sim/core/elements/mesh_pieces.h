// The separate pieces of a mesh: groups of elements joined through shared nodes. A piece that
// shares no node with the rest moves on its own, which a body made from a surface should warn of.
#pragma once

#include <vector>

#include "deformable_sim/core/elements/mesh.h"

namespace deformable_sim::core {

/// Per element (the tetrahedra, then the cells), the index of its piece; pieces are numbered
/// 0, 1, ... in the order of their first element.
std::vector<int> elementPieces(const Mesh& mesh);

}  // namespace deformable_sim::core
