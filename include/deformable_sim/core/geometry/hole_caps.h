// Whether a surface is closed, and the caps that close it when it is not: a fan of triangles over
// each hole. The ray count (ray_winding.h) needs a closed surface; voxelize measures the volume
// of an open one closed by these caps.
#pragma once

#include "deformable_sim/core/geometry/triangle_mesh.h"

namespace deformable_sim::core {

/// Whether every edge of `surface` is used as often from a to b as from b to a (by vertex
/// index): the surface is closed, and RayWinding gives its winding number.
bool isClosedSurface(const TriangleMesh& surface);

/// Triangles that close every hole of `surface`: for each edge used more often one way than the
/// other, as many triangles from it, reversed, to its hole's apex (the mean of the vertices of the
/// hole: the open edges that share vertices with it). The vertices are the surface's, then one
/// apex per hole; the triangles only the caps' (none for a closed surface). The surface's
/// triangles and these together are closed.
TriangleMesh holeCaps(const TriangleMesh& surface);

}  // namespace deformable_sim::core
