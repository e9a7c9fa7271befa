#include "deformable_sim/core/surface_bodies/ray_winding.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <utility>

namespace deformable_sim::core {

namespace {

// The first and last cell along each axis of the box of triangle t, clamped to the grid (a vertex
// a rounding off it still counts): the same floor as a query's, so that the cell holding a
// crossing has the triangle.
std::pair<Eigen::Array3i, Eigen::Array3i> boxCells(const TriangleMesh& surface, int t,
                                                   const VoxelGrid& grid) {
  const Eigen::Array3i last = grid.cells.array() - 1;
  const auto cellOf = [&](const Eigen::Vector3d& p) -> Eigen::Array3i {
    return ((p - grid.origin).array() / grid.cell_size).floor().cast<int>().max(0).min(last);
  };
  const Eigen::Vector3d& a = surface.vertices[surface.triangles[t][0]];
  const Eigen::Vector3d& b = surface.vertices[surface.triangles[t][1]];
  const Eigen::Vector3d& c = surface.vertices[surface.triangles[t][2]];
  return {cellOf(a.cwiseMin(b).cwiseMin(c)), cellOf(a.cwiseMax(b).cwiseMax(c))};
}

}  // namespace

double rayBinEntries(const TriangleMesh& surface, const VoxelGrid& grid) {
  double sum = 0.0;
  for (int t = 0; t < static_cast<int>(surface.triangles.size()); ++t) {
    const auto [low, high] = boxCells(surface, t, grid);
    sum += (high - low + 1).cast<double>().prod();
  }
  return sum;
}

RayWinding::RayWinding(const TriangleMesh& surface, const VoxelGrid& grid)
    : surface_(surface), grid_(grid), bins_(grid.numCells()) {
  yz_boxes_.reserve(surface.triangles.size());
  for (int t = 0; t < static_cast<int>(surface.triangles.size()); ++t) {
    const Eigen::Vector3d& a = surface.vertices[surface.triangles[t][0]];
    const Eigen::Vector3d& b = surface.vertices[surface.triangles[t][1]];
    const Eigen::Vector3d& c = surface.vertices[surface.triangles[t][2]];
    yz_boxes_.push_back({std::min({a.y(), b.y(), c.y()}), std::max({a.y(), b.y(), c.y()}),
                         std::min({a.z(), b.z(), c.z()}), std::max({a.z(), b.z(), c.z()})});
    const auto [low, high] = boxCells(surface, t, grid);
    for (int k = low.z(); k <= high.z(); ++k) {
      for (int j = low.y(); j <= high.y(); ++j) {
        for (int i = low.x(); i <= high.x(); ++i) bins_[grid.cellIndex({i, j, k})].push_back(t);
      }
    }
  }
  const std::vector<std::vector<int>>& bins = bins_;
  binned_before_.resize(grid.numCells());
  for (int k = 0; k < grid.cells.z(); ++k) {
    for (int j = 0; j < grid.cells.y(); ++j) {
      long sum = 0;
      for (int i = 0; i < grid.cells.x(); ++i) {
        const long index = grid.cellIndex({i, j, k});
        binned_before_[index] = sum;
        sum += static_cast<long>(bins[index].size());
      }
    }
  }
}

int RayWinding::side(int u, int v, double y, double z) const {
  if (u > v) return -side(v, u, y, z);
  const Eigen::Vector3d& a = surface_.vertices[u];
  const Eigen::Vector3d& b = surface_.vertices[v];
  // The 2D cross product (b - a) x (p - a) in (y, z) at p = (y + e, z + e^2):
  // s0 - (b.z - a.z) e + (b.y - a.y) e^2; its sign is that of its first term that is not 0.
  const double s0 = (b.y() - a.y()) * (z - a.z()) - (b.z() - a.z()) * (y - a.y());
  if (s0 != 0.0) return s0 > 0.0 ? 1 : -1;
  if (b.z() != a.z()) return b.z() < a.z() ? 1 : -1;
  if (b.y() != a.y()) return b.y() > a.y() ? 1 : -1;
  return 0;
}

bool RayWinding::meets(int t, double y, double z, double& x, int& sign) const {
  const Eigen::Vector3i& tri = surface_.triangles[t];
  sign = side(tri[0], tri[1], y, z);
  if (sign == 0 || side(tri[1], tri[2], y, z) != sign || side(tri[2], tri[0], y, z) != sign) {
    return false;
  }
  const Eigen::Vector3d& a = surface_.vertices[tri[0]];
  const Eigen::Vector3d& b = surface_.vertices[tri[1]];
  const Eigen::Vector3d& c = surface_.vertices[tri[2]];
  const Eigen::Vector3d normal = (b - a).cross(c - a);
  if (normal.x() == 0.0) return false;  // only a perturbed ray meets it: on no cell's row
  x = a.x() - (normal.y() * (y - a.y()) + normal.z() * (z - a.z())) / normal.x();
  // Rounding may take a steep triangle's x a little out of it: back into its span.
  x = std::clamp(x, std::min({a.x(), b.x(), c.x()}), std::max({a.x(), b.x(), c.x()}));
  return true;
}

int RayWinding::crossings(double from, double y, double z, int j, int k, int begin, int end,
                          bool upwards) const {
  const double h = grid_.cell_size;
  const int last = grid_.cells.x() - 1;
  int sum = 0;
  for (int i = begin; i < end; ++i) {
    for (int t : bins_[grid_.cellIndex({i, j, k})]) {
      const std::array<double, 4>& box = yz_boxes_[t];
      if (y < box[0] || y > box[1] || z < box[2] || z > box[3]) continue;
      double x = 0.0;
      int sign = 0;
      // A crossing at x == from counts along +x, not along -x: q is taken as moved by an
      // infinitesimal towards -x, so that a point on a face is on one side of it in every row.
      if (!meets(t, y, z, x, sign) || !(upwards ? x >= from : x < from)) continue;
      // A triangle in the bins of several cells along the row counts in the cell that holds
      // the crossing, once.
      if (std::clamp(static_cast<int>(std::floor((x - grid_.origin.x()) / h)), 0, last) == i) {
        sum += sign;
      }
    }
  }
  return sum;
}

int RayWinding::at(const Eigen::Vector3d& q) const {
  const Eigen::Array3i c = ((q - grid_.origin).array() / grid_.cell_size)
                               .floor()
                               .cast<int>()
                               .max(0)
                               .min(grid_.cells.array() - 1);
  const int n = grid_.cells.x();
  const long row_end = grid_.cellIndex({n - 1, c.y(), c.z()});
  const long row_total = binned_before_[row_end] + static_cast<long>(bins_[row_end].size());
  const long index = grid_.cellIndex(c.matrix());
  const long below = binned_before_[index];
  const long above = row_total - below - static_cast<long>(bins_[index].size());
  // Along +x, w(q) is the sum of the signs met beyond q (0 past the surface); along -x, the
  // negated sum of those met before q.
  if (above <= below) return crossings(q.x(), q.y(), q.z(), c.y(), c.z(), c.x(), n, true);
  return -crossings(q.x(), q.y(), q.z(), c.y(), c.z(), 0, c.x() + 1, false);
}

}  // namespace deformable_sim::core
