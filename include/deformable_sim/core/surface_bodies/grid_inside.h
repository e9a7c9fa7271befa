// Whether points of a voxel grid are inside a surface: the generalized winding number (Jacobson et
// al. 2013) is at least 1/2 there, found far more cheaply than by summing solid angles.
//
// A closed surface's winding number is a whole number off it, which a ray's crossings count
// exactly (ray_winding.h). An open one's is that of the surface closed by caps over its holes
// (hole_caps.h), so counted, less the caps' own: a tree over the caps' few triangles, asked only
// where the caps could move the answer (they subtend at most area / (4 pi d^2) of a sphere from
// a point at distance d; past a few holes, everywhere). A surface whose caps would cross much of
// the grid (its triangles face every which way), or whose triangles' boxes would fill much of it
// many times over (large triangles slanting across a fine grid), is asked by the generalized
// winding number's tree instead: slow, but sure, and no bins.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "deformable_sim/core/geometry/triangle_mesh.h"
#include "deformable_sim/core/geometry/winding_number.h"
#include "deformable_sim/core/surface_bodies/ray_winding.h"
#include "deformable_sim/core/surface_bodies/voxelization.h"

namespace deformable_sim::core {

class GridInside {
 public:
  /// Both must outlive this object, which must stay where it is made (the ray counter holds its
  /// members).
  GridInside(const TriangleMesh& surface, const VoxelGrid& grid);
  GridInside(const GridInside&) = delete;
  GridInside& operator=(const GridInside&) = delete;

  /// Whether q, a point inside the grid on no face between its cells, is inside the surface.
  bool at(const Eigen::Vector3d& q) const;

  /// The caps over the surface's holes (holeCaps), however points are asked: no triangle for a
  /// closed surface.
  const TriangleMesh& caps() const { return caps_; }
  /// Whether points are asked by counting a ray's crossings; if not, by the generalized winding
  /// number's tree over the whole surface.
  bool countsRays() const { return rays_.has_value(); }

 private:
  /// A hole's cap seen from afar: it lies within `radius` of `apex` and has `area`.
  struct CapBound {
    Eigen::Vector3d apex;
    double radius = 0.0, area = 0.0;  ///< m, m^2
  };
  /// Fills cap_bounds_, one per hole, unless there are more than a few holes.
  void boundCaps();
  /// An upper bound on the caps' winding number at q, by their area and distance.
  double capBound(const Eigen::Vector3d& q) const;

  TriangleMesh caps_;                 ///< over the holes; no triangle for a closed surface
  TriangleMesh closed_;               ///< the surface and its caps, when there are caps
  std::vector<CapBound> cap_bounds_;  ///< empty past a few holes: the caps' tree is always asked
  std::optional<RayWinding> rays_;
  std::optional<WindingNumber> cap_winding_;
  /// Instead, for a surface whose caps or triangles would bin into much of the grid: the
  /// generalized winding number of the whole surface, slow but sure.
  std::optional<WindingNumber> whole_winding_;
};

}  // namespace deformable_sim::core
