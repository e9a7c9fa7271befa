#include "deformable_sim/core/voxelization.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "deformable_sim/core/box_mesh.h"
#include "deformable_sim/core/box_occupancy.h"
#include "deformable_sim/core/cell.h"
#include "deformable_sim/core/mesh_pieces.h"
#include "deformable_sim/core/winding_number.h"

namespace deformable_sim::core {

namespace {

// An extent within this many cells of a whole number of them is that whole number: a box of
// 1 m cut into cells of 0.1 m is ten cells, not eleven, also from an STL's single precision
// (a relative error near 6e-8 of each coordinate).
constexpr double kWholeCellTolerance = 1e-5;

Eigen::AlignedBox3d boundingBox(const TriangleMesh& surface) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3i& t : surface.triangles) {
    for (int c = 0; c < 3; ++c) box.extend(surface.vertices[t[c]]);
  }
  return box;
}

// Per grid cell, the triangles that may cross it.
std::vector<std::vector<int>> binTriangles(const TriangleMesh& surface, const VoxelGrid& grid) {
  std::vector<std::vector<int>> bins(grid.numCells());
  const double h = grid.cell_size;
  const double margin = 1e-9 * h;
  const Eigen::Array3i last = grid.cells.array() - 1;
  for (int t = 0; t < static_cast<int>(surface.triangles.size()); ++t) {
    Eigen::AlignedBox3d box;
    for (int c = 0; c < 3; ++c) box.extend(surface.vertices[surface.triangles[t][c]]);
    const Eigen::Array3i low = ((box.min() - grid.origin).array() / h - kWholeCellTolerance)
                                   .floor()
                                   .cast<int>()
                                   .max(0)
                                   .min(last);
    const Eigen::Array3i high = ((box.max() - grid.origin).array() / h + kWholeCellTolerance)
                                    .floor()
                                    .cast<int>()
                                    .max(0)
                                    .min(last);
    for (int k = low.z(); k <= high.z(); ++k) {
      for (int j = low.y(); j <= high.y(); ++j) {
        for (int i = low.x(); i <= high.x(); ++i) {
          const Eigen::Vector3i cell(i, j, k);
          if (triangleMayCrossCube(surface, t, grid.cellMin(cell), h, margin)) {
            bins[grid.cellIndex(cell)].push_back(t);
          }
        }
      }
    }
  }
  return bins;
}

// f(i, j, k) for every (i, j, k) of a grid of `size`, x fastest.
template <typename Function>
void forEachPoint(const Eigen::Vector3i& size, Function f) {
  for (int k = 0; k < size.z(); ++k) {
    for (int j = 0; j < size.y(); ++j) {
      for (int i = 0; i < size.x(); ++i) f(i, j, k);
    }
  }
}

bool holdsMaterial(const OctantFractions& octants) {
  for (double f : octants) {
    if (f > 0.0) return true;
  }
  return false;
}

// The hexahedra of the cells with a fraction > 0 and the grid nodes they use, both in x-fastest
// order, as makeBoxMesh numbers them.
void buildMesh(const VoxelGrid& grid, const std::vector<OctantFractions>& fractions,
               Voxelization& result) {
  const Eigen::Vector3i n = grid.cells.array() + 1;
  auto grid_node = [&](int i, int j, int k) {
    return i + static_cast<long>(n.x()) * (j + static_cast<long>(n.y()) * k);
  };
  std::vector<int> node_of(static_cast<size_t>(n.x()) * n.y() * n.z(), -1);
  result.cell_at.assign(grid.numCells(), -1);
  static constexpr int kCorners[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                         {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  forEachPoint(grid.cells, [&](int i, int j, int k) {
    if (!holdsMaterial(fractions[grid.cellIndex({i, j, k})])) return;
    for (const auto& c : kCorners) node_of[grid_node(i + c[0], j + c[1], k + c[2])] = 0;
  });
  Mesh& mesh = result.mesh;
  mesh.incompatible_modes = true;
  forEachPoint(n, [&](int i, int j, int k) {
    int& node = node_of[grid_node(i, j, k)];
    if (node < 0) return;
    node = mesh.numNodes();
    mesh.positions.push_back(grid.origin + grid.cell_size * Eigen::Vector3d(i, j, k));
    mesh.node_numbers.push_back(mesh.numNodes());  // from 1
  });
  forEachPoint(grid.cells, [&](int i, int j, int k) {
    const long index = grid.cellIndex({i, j, k});
    if (!holdsMaterial(fractions[index])) return;
    Cell cell{CellType::kHexahedron, {}};
    for (int c = 0; c < 8; ++c) {
      cell.nodes[c] =
          node_of[grid_node(i + kCorners[c][0], j + kCorners[c][1], k + kCorners[c][2])];
    }
    result.cell_at[index] = static_cast<int>(mesh.cells.size());
    mesh.cells.push_back(cell);
    mesh.cell_fractions.push_back(fractions[index]);
  });
}

std::vector<int> pieceSizes(const Mesh& mesh) {
  std::vector<int> sizes;
  for (int piece : elementPieces(mesh)) {
    if (piece >= static_cast<int>(sizes.size())) sizes.resize(piece + 1, 0);
    ++sizes[piece];
  }
  std::sort(sizes.rbegin(), sizes.rend());
  return sizes;
}

}  // namespace

VoxelGrid voxelGridFor(const TriangleMesh& surface, const VoxelSettings& settings) {
  const Eigen::AlignedBox3d box = boundingBox(surface);
  if (box.isEmpty()) throw std::invalid_argument("voxel grid: the surface has no triangle");
  const Eigen::Vector3d extent = box.sizes();
  VoxelGrid grid;
  if (settings.cell_size > 0.0 && std::isfinite(settings.cell_size)) {
    grid.cell_size = settings.cell_size;
  } else if (settings.longest_side_cells >= 1) {
    grid.cell_size = extent.maxCoeff() / settings.longest_side_cells;
  } else {
    throw std::invalid_argument("voxel grid: needs a cell size > 0 or a number of cells >= 1");
  }
  if (!(grid.cell_size > 0.0)) throw std::invalid_argument("voxel grid: the surface is a point");
  const Eigen::Array3d cells =
      (extent.array() / grid.cell_size - kWholeCellTolerance).ceil().max(1.0);
  if (cells.prod() > static_cast<double>(kMaxBoxMeshCells)) {
    throw std::invalid_argument("voxel grid: more than " + std::to_string(kMaxBoxMeshCells) +
                                " cells; choose a larger cell size");
  }
  grid.cells = cells.cast<int>();
  grid.origin = box.center() - 0.5 * grid.cell_size * cells.matrix();
  return grid;
}

Voxelization voxelize(const TriangleMesh& surface, const VoxelGrid& grid, int levels) {
  const WindingNumber winding(surface);
  const std::vector<std::vector<int>> bins = binTriangles(surface, grid);
  std::vector<OctantFractions> fractions(grid.numCells());
  forEachPoint(grid.cells, [&](int i, int j, int k) {
    const Eigen::Vector3i cell(i, j, k);
    const long index = grid.cellIndex(cell);
    // A cell no triangle crosses is all in or all out: one query decides.
    if (bins[index].empty()) {
      fractions[index].fill(winding.at(grid.cellMin(cell).array() + 0.5 * grid.cell_size) >= 0.5);
    } else {
      fractions[index] = octantFractions(surface, winding, bins[index], grid.cellMin(cell),
                                         grid.cell_size, std::max(levels, 1));
    }
  });
  Voxelization result;
  result.grid = grid;
  buildMesh(grid, fractions, result);
  if (result.mesh.cells.empty()) {
    throw std::invalid_argument(
        "the surface encloses no volume: no grid cell is inside it (is it open, or a sheet?)");
  }
  result.enclosed_volume = enclosedVolume(surface);
  result.piece_sizes = pieceSizes(result.mesh);
  return result;
}

double enclosedVolume(const TriangleMesh& surface) {
  if (surface.vertices.empty()) return 0.0;
  // About a vertex rather than the origin: less cancellation for a part far from it.
  const Eigen::Vector3d& o = surface.vertices.front();
  double six_volume = 0.0;
  for (const Eigen::Vector3i& t : surface.triangles) {
    const Eigen::Vector3d a = surface.vertices[t[0]] - o;
    six_volume += a.dot((surface.vertices[t[1]] - o).cross(surface.vertices[t[2]] - o));
  }
  return six_volume / 6.0;
}

double partialCellMassFraction(const Mesh& mesh) {
  double partial = 0.0, total = 0.0;
  for (size_t c = 0; c < mesh.cells.size(); ++c) {
    const Cell& cell = mesh.cells[c];
    const double volume =
        mesh.cellFraction(c) * computeCellRest(cell.type, cellCorners(cell, mesh.positions)).volume;
    total += volume;
    if (mesh.cellFraction(c) < 1.0) partial += volume;
  }
  return total > 0.0 ? partial / total : 0.0;
}

}  // namespace deformable_sim::core
