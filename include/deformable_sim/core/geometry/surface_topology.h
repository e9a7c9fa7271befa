// How the triangles of a surface join through their edges: the rims of holes (open edges), edges
// that more than two triangles share, the separate shells, and the triangles that face against
// their neighbours.
#pragma once

#include <vector>

#include "deformable_sim/core/geometry/triangle_mesh.h"

namespace deformable_sim::core {

struct SurfaceTopology {
  int open_edges = 0;         ///< edges of one triangle only
  int overused_edges = 0;     ///< edges of three or more triangles (non-manifold)
  int shells = 0;             ///< groups of triangles joined through shared edges
  std::vector<int> shell_of;  ///< per triangle, its shell in 0 .. shells - 1
  /// Per shell, 1 when every edge of its triangles is shared by exactly two: it bounds a volume.
  std::vector<char> shell_closed;
  /// Per triangle, 1 when it faces against most of the triangles it is joined to through
  /// edges of two (its corners run the shared edge the same way as its neighbour's): turning
  /// these makes each such group face one way.
  std::vector<char> against_neighbours;
  int misoriented = 0;  ///< how many triangles against_neighbours marks
};

/// The topology of `surface` (valid indices, no triangle with a corner twice). Edges are pairs of
/// vertex indices: positions that coincide but are different vertices do not join.
SurfaceTopology surfaceTopology(const TriangleMesh& surface);

}  // namespace deformable_sim::core
