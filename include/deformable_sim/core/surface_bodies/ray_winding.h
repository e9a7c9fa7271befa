// The winding number of a closed surface at points of a voxel grid, counted exactly: the signed
// number of its triangles that the ray from the point along +x crosses (+1 for a triangle facing
// +x, -1 for one facing -x). For a surface whose every edge is used as often in each direction
// (closed, though it may cut through itself) this is the generalized winding number
// (winding_number.h) at every point off the surface, to the bit. An open surface is closed by
// caps over its holes (hole_caps.h): its winding number is that of surface and caps, counted so,
// less that of the caps alone, a few triangles.
//
// A ray through an edge or a vertex is moved by (0, e, e^2) for an infinitesimal e (simulation of
// simplicity, Edelsbrunner and Muecke 1990): each edge's side is computed from its lower-numbered
// vertex, so the two triangles of an edge see it alike and the ray crosses exactly one of them.
// A point on a face is likewise moved by an infinitesimal towards -x: a triangle at its very x
// counts along +x and not along -x, so that it is on the same side whichever way its row is
// walked.
// A query walks the grid's row of cells from the point's cell to the nearer end (the one with
// fewer triangles binned on the way: along -x the crossings count with opposite sign), testing
// only the triangles binned there (by bounding box: a crossing at x lies in the bin of the cell
// that holds x, where it is counted once), most by their yz box alone: a few dozen cheap tests,
// against the thousands of solid angles of a tree query.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "deformable_sim/core/geometry/triangle_mesh.h"
#include "deformable_sim/core/surface_bodies/voxelization.h"

namespace deformable_sim::core {

/// How many (cell, triangle) entries RayWinding(surface, grid) bins: per triangle, the cells of
/// `grid` its bounding box overlaps. Counted without binning, so that a caller can refuse a
/// surface of large triangles slanting across a fine grid (their boxes' volumes, summed, can
/// reach the triangles times the cells) before anything is allocated.
double rayBinEntries(const TriangleMesh& surface, const VoxelGrid& grid);

class RayWinding {
 public:
  /// Bins the triangles into the cells of `grid` their bounding boxes overlap (clamped to the
  /// grid: a vertex a rounding off the grid still counts). Both must outlive this object.
  RayWinding(const TriangleMesh& surface, const VoxelGrid& grid);

  /// The winding number at q, a point inside the grid that lies on no face between its cells.
  /// Allocates nothing.
  int at(const Eigen::Vector3d& q) const;

 private:
  /// The sum of the signs of the triangles the line {(x, y, z)} meets at x >= from (`upwards`)
  /// or x < from, counted in cells [begin, end) of the row (j, k).
  int crossings(double from, double y, double z, int j, int k, int begin, int end,
                bool upwards) const;
  /// Where the line {(x, y, z)} meets triangle t, when it does: its x, m, and +1 (the triangle
  /// faces +x) or -1.
  bool meets(int t, double y, double z, double& x, int& sign) const;
  /// The side of (y, z) + (0, e, e^2) of the edge from vertex u to v seen along +x: +1 left,
  /// -1 right, 0 for an edge of no length in the yz-plane.
  int side(int u, int v, double y, double z) const;

  const TriangleMesh& surface_;
  const VoxelGrid& grid_;
  std::vector<std::vector<int>> bins_;  ///< per grid cell, the triangles whose box overlaps it
  std::vector<std::array<double, 4>> yz_boxes_;  ///< per triangle: low y, high y, low z, high z
  std::vector<long> binned_before_;  ///< per grid cell: triangles binned before it in its row
};

}  // namespace deformable_sim::core
