// Where a surface passes through itself: the pairs of its triangles that cross, found through a
// bounding-box tree (core/geometry/triangle_aabb_tree.h) so that a scan of 70 000 triangles takes a
// few hundredths of a second.
#pragma once

#include "deformable_sim/core/geometry/triangle_mesh.h"

namespace deformable_sim::core {

struct SelfCrossings {
  int pairs = 0;         ///< pairs of triangles that cross (core/geometry/triangles_cross.h)
  bool complete = true;  ///< false: the check stopped after its budget of candidates
  long candidates = 0;   ///< pairs the tree gave and the check examined, tested or not
};

/// The pairs of triangles of `surface` that cross, except pairs that share a vertex (neighbours
/// touch by construction, and a fold at a shared corner is left alone). Stops after examining
/// `max_candidates_per_triangle` times the number of triangles candidate pairs (those whose boxes
/// the tree finds overlapping, each pair seen from both sides, tested or not), so that a soup of
/// triangles piled in one place, or a fan of many about one vertex (a CAD cylinder's end: each
/// of its triangles is a candidate of every other), cannot take quadratic time. The default lets
/// a cylinder's ends of a few hundred triangles each be checked whole.
SelfCrossings selfCrossings(const TriangleMesh& surface, int max_candidates_per_triangle = 256);

}  // namespace deformable_sim::core
