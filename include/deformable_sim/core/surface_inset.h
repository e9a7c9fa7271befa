// How far inside each node of a body made from a surface that surface lies at rest: the node's
// inset. The grid's cells cover the surface, so its boundary nodes stand up to a cell outside it;
// an obstacle lets each node that far in (core/contact.h), and two bodies touch where their
// surfaces meet (core/body_contact.h), so that the surface drawn and reported, not the grid
// around it, is what rests on a table, on another body or in a gripper.
#pragma once

#include <vector>

#include "deformable_sim/core/mesh.h"
#include "deformable_sim/core/triangle_mesh.h"

namespace deformable_sim::core {

/// Per node of `mesh`, its distance from `surface` (both at rest, m) where the node lies outside
/// it (generalized winding number below 1/2), 0 inside. Allocates.
std::vector<double> surfaceInsets(const Mesh& mesh, const TriangleMesh& surface);

}  // namespace deformable_sim::core
