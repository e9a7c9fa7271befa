// A body's grid and drawn surface from a triangle surface: voxelize, then embed the surface in
// the cells (core/voxelization.h, core/embedded_surface.h).
#pragma once

#include <string>
#include <vector>

#include "deformable_sim/core/embedded_surface.h"
#include "deformable_sim/core/triangle_mesh.h"
#include "deformable_sim/core/voxelization.h"

namespace deformable_sim::core {

struct SurfaceBody {
  Voxelization voxels;
  EmbeddedSurface surface;
};

/// Voxelizes `surface` on the grid `settings` ask for and embeds it. Throws std::invalid_argument
/// for settings that make no grid and for a surface that encloses nothing. A warning naming the
/// separate pieces is appended to `warnings`.
SurfaceBody bodyFromSurface(TriangleMesh surface, const VoxelSettings& settings,
                            std::vector<std::string>* warnings);

/// "3 separate pieces (120, 14 and 3 cells) that move independently", or empty for one piece.
std::string piecesWarning(const std::vector<int>& piece_sizes);

}  // namespace deformable_sim::core
