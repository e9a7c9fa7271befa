#include "deformable_sim/core/surface_bodies/embedded_surface.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <limits>
#include <stdexcept>

namespace deformable_sim::core {

namespace {

// Squared distance from p to the cube [min, min + h].
double squaredDistanceToCube(const Eigen::Vector3d& p, const Eigen::Vector3d& min, double h) {
  const Eigen::Vector3d below = (min - p).array().max(0.0).matrix();
  const Eigen::Vector3d above = (p.array() - min.array() - h).max(0.0).matrix();
  return (below + above).squaredNorm();
}

// The kept cell that holds p, or the kept cell nearest to it.
int holdingCell(const Voxelization& voxels, const Eigen::Vector3d& p) {
  const VoxelGrid& grid = voxels.grid;
  const Eigen::Vector3i c = ((p - grid.origin) / grid.cell_size)
                                .array()
                                .floor()
                                .cast<int>()
                                .max(0)
                                .min(grid.cells.array() - 1);
  const int direct = voxels.cell_at[grid.cellIndex(c)];
  if (direct >= 0) return direct;
  int nearest = -1;
  double best = std::numeric_limits<double>::infinity();
  auto consider = [&](int k) {
    const Eigen::Vector3d& min = voxels.mesh.positions[voxels.mesh.cells[k].nodes[0]];
    const double d = squaredDistanceToCube(p, min, grid.cell_size);
    if (d < best) {
      best = d;
      nearest = k;
    }
  };
  // The neighbours first: a vertex lies at most a cell or two away from the cells kept, unless
  // the surface is far thinner than a cell.
  const Eigen::Array3i low = (c.array() - 2).max(0),
                       high = (c.array() + 2).min(grid.cells.array() - 1);
  for (int z = low.z(); z <= high.z(); ++z) {
    for (int y = low.y(); y <= high.y(); ++y) {
      for (int x = low.x(); x <= high.x(); ++x) {
        const int k = voxels.cell_at[grid.cellIndex({x, y, z})];
        if (k >= 0) consider(k);
      }
    }
  }
  if (nearest >= 0) return nearest;
  for (int k = 0; k < static_cast<int>(voxels.mesh.cells.size()); ++k) consider(k);
  return nearest;
}

}  // namespace

std::array<double, 8> trilinearWeights(const Eigen::Vector3d& t) {
  const Eigen::Vector3d s = Eigen::Vector3d::Ones() - t;
  // Gmsh's hexahedron order: the bottom face counter-clockwise from (0, 0, 0), then the top.
  return {s.x() * s.y() * s.z(), t.x() * s.y() * s.z(), t.x() * t.y() * s.z(),
          s.x() * t.y() * s.z(), s.x() * s.y() * t.z(), t.x() * s.y() * t.z(),
          t.x() * t.y() * t.z(), s.x() * t.y() * t.z()};
}

EmbeddedSurface::EmbeddedSurface(TriangleMesh surface, const Voxelization& voxels)
    : triangles_(std::move(surface.triangles)), rest_(std::move(surface.vertices)) {
  const Mesh& mesh = voxels.mesh;
  embeddings_.resize(rest_.size());
  for (size_t v = 0; v < rest_.size(); ++v) {
    Embedding& e = embeddings_[v];
    e.cell = holdingCell(voxels, rest_[v]);
    const Cell& cell = mesh.cells[e.cell];
    // Node 0 is the cell's lowest corner (Gmsh order, as voxelize builds it).
    const Eigen::Vector3d local =
        (rest_[v] - mesh.positions[cell.nodes[0]]) / voxels.grid.cell_size;
    e.weights = trilinearWeights(local);
    e.nodes = cell.nodes;
    largest_node_ = std::max(largest_node_, *std::max_element(e.nodes.begin(), e.nodes.end()));
  }
  positions_ = rest_;
  normals_.resize(rest_.size());
  updateNormals();
}

void EmbeddedSurface::update(const Eigen::VectorXd& x) {
  for (size_t v = 0; v < embeddings_.size(); ++v) {
    const Embedding& e = embeddings_[v];
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (int k = 0; k < 8; ++k) p += e.weights[k] * x.segment<3>(3 * e.nodes[k]);
    positions_[v] = p;
  }
  updateNormals();
}

void EmbeddedSurface::updateNormals() {
  for (Eigen::Vector3d& n : normals_) n.setZero();
  for (const Eigen::Vector3i& t : triangles_) {
    // The cross product's length is twice the area: the sum is weighted by area.
    const Eigen::Vector3d n =
        (positions_[t[1]] - positions_[t[0]]).cross(positions_[t[2]] - positions_[t[0]]);
    for (int c = 0; c < 3; ++c) normals_[t[c]] += n;
  }
  for (Eigen::Vector3d& n : normals_) {
    const double length = n.norm();
    if (length > 0.0) n /= length;
  }
}

SurfacePoint vertexPoint(const EmbeddedSurface& surface, int v) {
  SurfacePoint point;
  point.shifts_cells = true;
  for (int k = 0; k < 8; ++k) {
    if (surface.weights(v)[k] == 0.0) continue;
    point.nodes[point.count] = surface.nodes(v)[k];
    point.weights[point.count++] = surface.weights(v)[k];
  }
  return point;
}

EmbeddedSurface embedInGrid(TriangleMesh surface, const Mesh& grid_mesh, const std::string& what) {
  const auto notAGrid = [&what]() {
    return std::invalid_argument(what + " is not a grid of cubes to embed a surface in");
  };
  if (grid_mesh.cells.empty() || !grid_mesh.tetrahedra.empty()) throw notAGrid();
  Voxelization voxels;
  voxels.mesh = grid_mesh;
  const std::vector<Eigen::Vector3d>& x = grid_mesh.positions;
  const Cell& first = grid_mesh.cells.front();
  if (first.size() != 8) throw notAGrid();
  VoxelGrid& grid = voxels.grid;
  grid.cell_size = (x[first.nodes[1]] - x[first.nodes[0]]).norm();
  grid.origin = x[first.nodes[0]];
  Eigen::Vector3d top = grid.origin;
  for (const Cell& cell : grid_mesh.cells) {
    if (cell.size() != 8) throw notAGrid();
    grid.origin = grid.origin.cwiseMin(x[cell.nodes[0]]);
    top = top.cwiseMax(x[cell.nodes[6]]);
  }
  if (!(grid.cell_size > 0.0)) throw notAGrid();
  grid.cells = ((top - grid.origin) / grid.cell_size).array().round().cast<int>().max(1);
  voxels.cell_at.assign(grid.numCells(), -1);
  for (size_t k = 0; k < grid_mesh.cells.size(); ++k) {
    const Eigen::Vector3d at = (x[grid_mesh.cells[k].nodes[0]] - grid.origin) / grid.cell_size;
    const Eigen::Vector3i c = at.array().round().cast<int>();
    if ((at - c.cast<double>()).norm() > 1e-6 || (c.array() >= grid.cells.array()).any()) {
      throw notAGrid();
    }
    voxels.cell_at[grid.cellIndex(c)] = static_cast<int>(k);
  }
  return EmbeddedSurface(std::move(surface), voxels);
}

}  // namespace deformable_sim::core
