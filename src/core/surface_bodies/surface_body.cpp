#include "deformable_sim/core/surface_bodies/surface_body.h"

#include <stdexcept>
#include <utility>

#include "deformable_sim/core/surface_bodies/surface_check.h"

namespace deformable_sim::core {

SurfaceBody bodyFromSurface(TriangleMesh surface, const VoxelSettings& settings,
                            std::vector<std::string>* warnings, int zero_area_dropped) {
  // First what the grid refuses outright (a coordinate that is not finite, too many cells): the
  // check would count a triangle with an infinite corner as one of zero area.
  voxelGridFor(surface, settings);
  const SurfaceCheck check = checkSurface(surface, zero_area_dropped);
  std::vector<std::string> found = surfaceWarnings(check);
  Voxelization voxels;
  try {
    voxels = voxelize(surface, voxelGridFor(surface, settings), settings.levels, settings.progress);
  } catch (const std::invalid_argument& e) {
    // What the check found often says why (a sheet is all open edges).
    std::string message = e.what();
    for (const std::string& w : found) message += "; " + w;
    throw std::invalid_argument(message);
  }
  if (warnings) warnings->insert(warnings->end(), found.begin(), found.end());
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
