#include "deformable_sim/core/surface_bodies/voxelization.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/elements/cell.h"
#include "deformable_sim/core/elements/mesh_pieces.h"
#include "deformable_sim/core/surface_bodies/box_occupancy.h"
#include "deformable_sim/core/surface_bodies/grid_inside.h"

namespace deformable_sim::core {

namespace {

// An extent within this many cells of a whole number of them is that whole number: a box of
// 1 m cut into cells of 0.1 m is ten cells, not eleven, also from an STL's single precision
// (a relative error near 6e-8 of each coordinate).
constexpr double kWholeCellTolerance = 1e-5;

// Of the vertices the triangles use. Throws std::invalid_argument naming a vertex with a
// coordinate that is not finite: it has no place in a grid.
Eigen::AlignedBox3d boundingBox(const TriangleMesh& surface) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3i& t : surface.triangles) {
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d& v = surface.vertices[t[c]];
      if (!v.allFinite()) {
        char text[160];
        std::snprintf(text, sizeof text, "vertex %d is (%g, %g, %g)", t[c] + 1, v.x(), v.y(),
                      v.z());
        throw std::invalid_argument(
            "voxel grid: the surface has coordinates that are not finite (NaN or infinite): " +
            std::string(text));
      }
      box.extend(v);
    }
  }
  return box;
}

// A count of cells as a whole number, or about one when it is too large for that.
std::string countText(double count) {
  char text[32];
  std::snprintf(text, sizeof text, count < 1e15 ? "%.0f" : "%.3g", count);
  return text;
}

std::string bytesText(double bytes) {
  char text[32];
  if (bytes >= 1e12) {
    std::snprintf(text, sizeof text, "%.3g TB", bytes / 1e12);
  } else if (bytes >= 1e9) {
    std::snprintf(text, sizeof text, "%.3g GB", bytes / 1e9);
  } else {
    std::snprintf(text, sizeof text, "%.3g MB", bytes / 1e6);
  }
  return text;
}

// "voxel grid: cells of 0.01 m make 10 x 20 x 30": the start of a refusal.
std::string gridText(const Eigen::Array3d& cells, double cell_size) {
  char size[32];
  std::snprintf(size, sizeof size, "%.6g m", cell_size);
  return "voxel grid: cells of " + std::string(size) + " make " + countText(cells.x()) + " x " +
         countText(cells.y()) + " x " + countText(cells.z());
}

// Refuses a grid of more than max_cells cells before anything is allocated, saying how many it
// would take and what that costs.
void checkCellCount(const Eigen::Array3d& cells, double cell_size, long max_cells) {
  const double count = cells.prod();
  if (count <= static_cast<double>(max_cells)) return;
  throw std::invalid_argument(
      gridText(cells, cell_size) + " = " + countText(count) + " cells, more than max_cells (" +
      std::to_string(max_cells) + "); voxelizing them would take " +
      bytesText(count * kVoxelBytesPerGridCell) + " and a body of them up to " +
      bytesText(count * kBodyBytesPerCell) + ". Choose a larger cell_size or fewer cells" +
      (max_cells < kMostGridCells
           ? ", or raise max_cells (a key of the body's mesh entry, beside cell_size)"
           : " (max_cells is at its most, what a mesh's int indices number)"));
}

// Refuses a grid whose cells or nodes int indices cannot number (a mesh's are int), whatever
// max_cells allows.
void checkIndexRange(const Eigen::Array3d& cells, double cell_size) {
  const double most = static_cast<double>(kMostGridCells);
  const double nodes = (cells + 1.0).prod();
  if (cells.maxCoeff() <= most && nodes <= most) return;
  throw std::invalid_argument(gridText(cells, cell_size) + " cells with " + countText(nodes) +
                              " nodes, more than a mesh can number (" +
                              std::to_string(kMostGridCells) +
                              " along a side and nodes in all, whatever max_cells says). Choose "
                              "a larger cell_size or fewer cells");
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

// Every grid cell's octant fractions, layer by layer along z, telling `progress` after each.
std::vector<OctantFractions> cellFractions(const TriangleMesh& surface, const VoxelGrid& grid,
                                           const std::vector<std::vector<int>>& bins,
                                           const InsideTest& inside, int levels,
                                           const VoxelProgress& progress) {
  std::vector<OctantFractions> fractions(grid.numCells());
  const long layer = static_cast<long>(grid.cells.x()) * grid.cells.y();
  if (progress) progress(0, grid.numCells());
  for (int k = 0; k < grid.cells.z(); ++k) {
    forEachPoint({grid.cells.x(), grid.cells.y(), 1}, [&](int i, int j, int) {
      const Eigen::Vector3i cell(i, j, k);
      const long index = grid.cellIndex(cell);
      // A cell no triangle crosses is all in or all out: one query decides.
      if (bins[index].empty()) {
        fractions[index].fill(inside(grid.cellMin(cell).array() + 0.5 * grid.cell_size));
      } else {
        fractions[index] = octantFractions(surface, inside, bins[index], grid.cellMin(cell),
                                           grid.cell_size, levels);
      }
    });
    if (progress) progress(layer * (k + 1), grid.numCells());
  }
  return fractions;
}

// Why no cell holds material: cells too large to see the part (fewer than two along every side
// of its bounding box), or a surface with no inside.
std::string nothingEnclosed(const TriangleMesh& surface, const VoxelGrid& grid) {
  const Eigen::Vector3d extent = boundingBox(surface).sizes();
  if ((extent.array() < 2.0 * grid.cell_size).all()) {
    char text[320];
    std::snprintf(text, sizeof text,
                  "the cell size %.6g m is too large for the part, %.3g x %.3g x %.3g m: no "
                  "cell is inside it; choose a cell size of at most %.3g m (a tenth of its "
                  "longest side) or give cells instead",
                  grid.cell_size, extent.x(), extent.y(), extent.z(), 0.1 * extent.maxCoeff());
    return text;
  }
  return "the surface encloses no volume: no grid cell is inside it (is it open, or a sheet?)";
}

}  // namespace

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
  checkCellCount(cells, grid.cell_size, settings.max_cells);
  checkIndexRange(cells, grid.cell_size);
  grid.cells = cells.cast<int>();
  grid.origin = box.center() - 0.5 * grid.cell_size * cells.matrix();
  return grid;
}

Voxelization voxelize(const TriangleMesh& surface, const VoxelGrid& grid, int levels,
                      const VoxelProgress& progress) {
  const std::vector<std::vector<int>> bins = binTriangles(surface, grid);
  const GridInside inside(surface, grid);
  const std::vector<OctantFractions> fractions = cellFractions(
      surface, grid, bins, [&inside](const Eigen::Vector3d& q) { return inside.at(q); },
      std::max(levels, 1), progress);
  Voxelization result;
  result.grid = grid;
  buildMesh(grid, fractions, result);
  if (result.mesh.cells.empty()) throw std::invalid_argument(nothingEnclosed(surface, grid));
  // An open surface encloses no volume of its own: closed by the caps over its holes (none for a
  // closed one), it encloses what the grid should hold.
  result.enclosed_volume = enclosedVolume(surface) + enclosedVolume(inside.caps());
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
