// A body's grid and drawn surface from a triangle surface: check it, voxelize, then embed the
// surface in the cells (surface_check.h, voxelization.h, embedded_surface.h of this folder).
#pragma once

#include <string>
#include <vector>

#include "deformable_sim/core/geometry/triangle_mesh.h"
#include "deformable_sim/core/surface_bodies/embedded_surface.h"
#include "deformable_sim/core/surface_bodies/voxelization.h"

namespace deformable_sim::core {

struct SurfaceBody {
  Voxelization voxels;
  EmbeddedSurface surface;
};

/// Checks and repairs `surface` (surface_check.h), voxelizes it on the grid `settings` ask
/// for and embeds it. Throws std::invalid_argument for settings that make no grid and for a
/// surface that encloses nothing. The check's warnings and one naming the separate pieces are
/// appended to `warnings`. `zero_area_dropped`: triangles a reader already dropped (their corners
/// coincided), counted in the check's warning.
SurfaceBody bodyFromSurface(TriangleMesh surface, const VoxelSettings& settings,
                            std::vector<std::string>* warnings, int zero_area_dropped = 0);

/// "3 separate pieces (120, 14 and 3 cells) that move independently", or empty for one piece.
std::string piecesWarning(const std::vector<int>& piece_sizes);

}  // namespace deformable_sim::core
