#include "deformable_sim/core/surface_bodies/grid_inside.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>

#include "deformable_sim/core/geometry/hole_caps.h"

namespace deformable_sim::core {

namespace {

// Caps that would cost more than this many bin entries per triangle of the surface and cell of
// the grid are not worth it: the generalized winding number's tree asks the surface instead.
// Caps over a few holes cover a few cells each; a surface whose triangles face every which way
// has open edges all over, and fans across the whole grid.
constexpr double kMostCapEntriesPerItem = 4.0;
// Nor the surface and caps together beyond this many: large triangles slanting across a fine
// grid (a long cylinder's sides, turned) would bin into most of its cells each.
constexpr double kMostBinEntriesPerItem = 16.0;
// Past this many holes their bounds cost more per query than they save: the caps' tree is asked
// at every point instead.
constexpr size_t kMostCapBounds = 16;

}  // namespace

GridInside::GridInside(const TriangleMesh& surface, const VoxelGrid& grid)
    : caps_(holeCaps(surface)) {
  const double items = static_cast<double>(surface.triangles.size() + grid.numCells());
  const double cap_entries = rayBinEntries(caps_, grid);
  if (cap_entries > kMostCapEntriesPerItem * items ||
      rayBinEntries(surface, grid) + cap_entries > kMostBinEntriesPerItem * items) {
    whole_winding_.emplace(surface);
    return;
  }
  if (caps_.triangles.empty()) {
    rays_.emplace(surface, grid);
    return;
  }
  closed_ = surface;
  closed_.vertices = caps_.vertices;
  closed_.triangles.insert(closed_.triangles.end(), caps_.triangles.begin(), caps_.triangles.end());
  rays_.emplace(closed_, grid);
  cap_winding_.emplace(caps_);
  boundCaps();
}

void GridInside::boundCaps() {
  // Each cap triangle is (b, a, apex): one bound per apex.
  std::map<int, CapBound> by_apex;
  for (const Eigen::Vector3i& t : caps_.triangles) {
    CapBound& bound = by_apex[t[2]];
    const Eigen::Vector3d& apex = caps_.vertices[t[2]];
    bound.apex = apex;
    for (int c = 0; c < 2; ++c) {
      bound.radius = std::max(bound.radius, (caps_.vertices[t[c]] - apex).norm());
    }
    bound.area += 0.5 * (caps_.vertices[t[0]] - apex).cross(caps_.vertices[t[1]] - apex).norm();
  }
  if (by_apex.size() > kMostCapBounds) return;
  for (const auto& [apex, bound] : by_apex) cap_bounds_.push_back(bound);
}
double GridInside::capBound(const Eigen::Vector3d& q) const {
  double sum = 0.0;
  for (const CapBound& cap : cap_bounds_) {
    const double gap = (q - cap.apex).norm() - cap.radius;
    if (!(gap > 0.0)) return INFINITY;
    sum += cap.area / (4.0 * M_PI * gap * gap);
  }
  return sum;
}

bool GridInside::at(const Eigen::Vector3d& q) const {
  if (whole_winding_) return whole_winding_->at(q) >= 0.5;
  const int count = rays_->at(q);
  if (!cap_winding_) return count >= 1;
  // Caps that subtend less than half a sphere cannot take a whole number across 1/2.
  if (!cap_bounds_.empty() && capBound(q) < 0.5) return count >= 1;
  return count - cap_winding_->at(q) >= 0.5;
}

}  // namespace deformable_sim::core
