// A body from a surface: the hexahedral cells of a regular grid that the surface encloses, each
// weighted by the fraction of it inside (Mesh::cell_fractions), so that the body's mass is the
// density times the enclosed volume and a cell that the surface cuts is as much softer.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/elements/mesh.h"
#include "deformable_sim/core/geometry/triangle_mesh.h"

namespace deformable_sim::core {

/// A regular grid of cubes: cell (i, j, k) spans origin + h (i, j, k) .. origin + h (i+1, j+1,
/// k+1).
struct VoxelGrid {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< m
  double cell_size = 1.0;                            ///< h, m
  Eigen::Vector3i cells = Eigen::Vector3i::Ones();

  long numCells() const { return static_cast<long>(cells.x()) * cells.y() * cells.z(); }
  long cellIndex(const Eigen::Vector3i& c) const {
    return c.x() + static_cast<long>(cells.x()) * (c.y() + static_cast<long>(cells.y()) * c.z());
  }
  Eigen::Vector3d cellMin(const Eigen::Vector3i& c) const {
    return origin + cell_size * c.cast<double>();
  }
};

/// Told how far voxelize is: `done` of the grid's `total` cells, from 0 to total, never less
/// than the last time. Called once per layer of cells (along z), so cheap enough to redraw a bar.
using VoxelProgress = std::function<void(long done, long total)>;

/// What a grid's cells cost, bytes: voxelizing and embedding the surface peak near
/// kVoxelBytesPerGridCell per cell of the grid; a body then needs about kBodyBytesPerCell per cell
/// it holds (elements, matrices, solver), up to every cell of the grid. Both measured as peak
/// resident memory on a box of 64k cells.
constexpr double kVoxelBytesPerGridCell = 300.0;
constexpr double kBodyBytesPerCell = 12000.0;

/// The most cells, and the most nodes, any grid may have whatever max_cells says: a mesh numbers
/// its nodes and cells by int.
constexpr long kMostGridCells = std::numeric_limits<int>::max();

/// How fine the grid is: cell_size if > 0, else longest_side_cells along the longest side of the
/// surface's bounding box.
struct VoxelSettings {
  double cell_size = 0.0;      ///< m
  int longest_side_cells = 0;  ///< cells along the bounding box's longest side
  /// Near the surface a cell is cut into 2^levels parts per axis to measure its fraction.
  int levels = 3;
  /// The most cells the grid may have (scene key max_cells of a surface body's mesh entry), at
  /// most kMostGridCells: a grid of more is refused before anything is allocated.
  long max_cells = kMaxBoxMeshCells;
  VoxelProgress progress;  ///< if set, told how far voxelize is
};

/// The grid that covers the bounding box of `surface` with whole cells, centred on it (an
/// extent that is a whole number of cells, within 1e-5 of one, is covered exactly). Throws
/// std::invalid_argument for settings that give no cell size, a surface with a coordinate that is
/// not finite, a grid of more than settings.max_cells cells (saying how many cells and about
/// how much memory it would take), or one that int indices cannot number: more than
/// kMostGridCells cells along a side or nodes in all, whatever settings.max_cells says.
VoxelGrid voxelGridFor(const TriangleMesh& surface, const VoxelSettings& settings);

/// Per cell of `grid` (VoxelGrid::cellIndex), the triangles of `surface` that may cross it: every
/// one that does, and some that pass within 1e-5 of a cell.
std::vector<std::vector<int>> binTriangles(const TriangleMesh& surface, const VoxelGrid& grid);

struct Voxelization {
  VoxelGrid grid;
  /// Hexahedra in the grid's x-fastest order, nodes likewise (numbered from 1), with
  /// cell_fractions: the same nodes and cells as makeBoxMesh for a box that fills the grid.
  Mesh mesh;
  std::vector<int> cell_at;  ///< per grid cell (VoxelGrid::cellIndex), its mesh cell or -1
  /// Of the surface, by the divergence theorem, with its holes closed by holeCaps (hole_caps.h)
  /// however points are asked, m^3. The ray count asks the surface so closed; the tree that asks
  /// a surface facing every which way (grid_inside.h) does not, and may hold more or less.
  double enclosed_volume = 0.0;
  /// Cells per separate piece (groups of cells that share no node), largest first.
  std::vector<int> piece_sizes;
};

/// The cells of `grid` with any part inside `surface` (generalized winding number >= 1/2), each
/// octant's fraction measured to a resolution of cell_size / 2^levels. Points are asked by
/// counting the triangles a ray crosses, with caps over any holes (grid_inside.h): the answers of
/// the generalized winding number, far faster. Single-threaded and deterministic. Throws
/// std::invalid_argument when no cell is inside (saying so when the cells are too large for the
/// part). `progress`, if set, is told how far it is.
Voxelization voxelize(const TriangleMesh& surface, const VoxelGrid& grid, int levels,
                      const VoxelProgress& progress = {});

/// The signed volume the triangles enclose, sum of a . (b x c) / 6, m^3: positive for a closed
/// surface facing outwards.
double enclosedVolume(const TriangleMesh& surface);

/// The part of the mass in cells the surface cuts (fraction < 1), of the whole.
double partialCellMassFraction(const Mesh& mesh);

}  // namespace deformable_sim::core
