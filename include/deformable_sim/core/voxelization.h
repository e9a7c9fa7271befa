// A body from a surface: the hexahedral cells of a regular grid that the surface encloses, each
// weighted by the fraction of it inside (Mesh::cell_fractions), so that the body's mass is the
// density times the enclosed volume and a cell that the surface cuts is as much softer.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "deformable_sim/core/mesh.h"
#include "deformable_sim/core/triangle_mesh.h"

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

/// How fine the grid is: cell_size if > 0, else longest_side_cells along the longest side of the
/// surface's bounding box.
struct VoxelSettings {
  double cell_size = 0.0;      ///< m
  int longest_side_cells = 0;  ///< cells along the bounding box's longest side
  /// Near the surface a cell is cut into 2^levels parts per axis to measure its fraction.
  int levels = 3;
};

/// The grid that covers the bounding box of `surface` with whole cells, centred on it (an
/// extent that is a whole number of cells, within 1e-5 of one, is covered exactly). Throws
/// std::invalid_argument for settings that give no cell size or more than kMaxBoxMeshCells cells.
VoxelGrid voxelGridFor(const TriangleMesh& surface, const VoxelSettings& settings);

struct Voxelization {
  VoxelGrid grid;
  /// Hexahedra in the grid's x-fastest order, nodes likewise (numbered from 1), with
  /// cell_fractions: the same nodes and cells as makeBoxMesh for a box that fills the grid.
  Mesh mesh;
  std::vector<int> cell_at;      ///< per grid cell (VoxelGrid::cellIndex), its mesh cell or -1
  double enclosed_volume = 0.0;  ///< of the surface, by the divergence theorem, m^3
  /// Cells per separate piece (groups of cells that share no node), largest first.
  std::vector<int> piece_sizes;
};

/// The cells of `grid` with any part inside `surface` (generalized winding number >= 1/2).
/// Throws std::invalid_argument when none is.
Voxelization voxelize(const TriangleMesh& surface, const VoxelGrid& grid, int levels);

/// The signed volume the triangles enclose, sum of a . (b x c) / 6, m^3: positive for a closed
/// surface facing outwards.
double enclosedVolume(const TriangleMesh& surface);

/// The part of the mass in cells the surface cuts (fraction < 1), of the whole.
double partialCellMassFraction(const Mesh& mesh);

}  // namespace deformable_sim::core
