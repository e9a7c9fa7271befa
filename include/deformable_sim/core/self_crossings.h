// Where a surface passes through itself: the pairs of its triangles that cross, found through a
// bounding-box tree (core/triangle_aabb_tree.h) so that a scan of 70 000 triangles takes a few
// hundredths of a second.
#pragma once

#include "deformable_sim/core/triangle_mesh.h"

namespace deformable_sim::core {

struct SelfCrossings {
  int pairs = 0;         ///< pairs of triangles that cross (core/triangles_cross.h)
  bool complete = true;  ///< false: the check stopped after its budget of pair tests
};

/// The pairs of triangles of `surface` that cross, except pairs that share a vertex (neighbours
/// touch by construction, and a fold at a shared corner is left alone). Stops after
/// `max_tests_per_triangle` times the number of triangles pair tests, so that a soup of
/// triangles piled in one place cannot take quadratic time.
SelfCrossings selfCrossings(const TriangleMesh& surface, int max_tests_per_triangle = 64);

}  // namespace deformable_sim::core
