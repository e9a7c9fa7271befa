#include "deformable_sim/core/surface_body.h"

#include <utility>

namespace deformable_sim::core {

SurfaceBody bodyFromSurface(TriangleMesh surface, const VoxelSettings& settings,
                            std::vector<std::string>* warnings) {
  Voxelization voxels =
      voxelize(surface, voxelGridFor(surface, settings), settings.levels, settings.progress);
  const std::string pieces = piecesWarning(voxels.piece_sizes);
  if (warnings && !pieces.empty()) warnings->push_back(pieces);
  // Embedded as a recording embeds it again from the grid alone, to the same bits: contact acts
  // on the vertices, and a replay must step them alike.
  EmbeddedSurface embedded = embedInGrid(std::move(surface), voxels.mesh, "the voxelized grid");
  return {std::move(voxels), std::move(embedded)};
}

std::string piecesWarning(const std::vector<int>& piece_sizes) {
  const size_t n = piece_sizes.size();
  if (n < 2) return "";
  std::string sizes;
  for (size_t k = 0; k < n; ++k) {
    sizes += (k == 0 ? "" : (k + 1 == n ? " and " : ", ")) + std::to_string(piece_sizes[k]);
  }
  return std::to_string(n) + " separate pieces (" + sizes +
         " cells) that share no node and move independently";
}

}  // namespace deformable_sim::core
