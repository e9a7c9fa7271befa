#include "deformable_sim/core/geometry/triangle_aabb_tree.h"

#include <algorithm>
#include <array>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace deformable_sim::core {

namespace {

constexpr int kLeafSize = 4;
// Median splits halve each range, so the depth stays below log2(triangles) + 1: 64 is enough
// for any mesh that fits in memory, and the query's stack needs no heap.
constexpr int kMaxDepth = 64;

double squaredDistanceToBox(const Eigen::Vector3d& p, const Eigen::Vector3d& min,
                            const Eigen::Vector3d& max) {
  const Eigen::Vector3d outside = (min - p).cwiseMax(p - max).cwiseMax(0.0);
  return outside.squaredNorm();
}

}  // namespace

TriangleAabbTree::TriangleAabbTree(const TriangleMesh& mesh) {
  const int count = static_cast<int>(mesh.triangles.size());
  if (count == 0) throw std::invalid_argument("a triangle tree needs at least one triangle");
  order_.resize(count);
  std::iota(order_.begin(), order_.end(), 0);
  centroids_.reserve(count);
  for (const Eigen::Vector3i& t : mesh.triangles) {
    centroids_.push_back((mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3.0);
  }
  nodes_.reserve(2 * (count / kLeafSize + 1));
  nodes_.emplace_back();
  build(mesh, 0, 0, count);
  centroids_ = {};
}

// Fills node `index` with the box of order_[begin, end) and splits it at the median centroid
// along the box's longest axis. Returns the depth of the subtree.
int TriangleAabbTree::build(const TriangleMesh& mesh, int index, int begin, int end) {
  Eigen::Vector3d min = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d max = -min;
  for (int k = begin; k < end; ++k) {
    for (int corner = 0; corner < 3; ++corner) {
      const Eigen::Vector3d& v = mesh.vertices[mesh.triangles[order_[k]][corner]];
      min = min.cwiseMin(v);
      max = max.cwiseMax(v);
    }
  }
  nodes_[index].min = min;
  nodes_[index].max = max;
  if (end - begin <= kLeafSize) {
    nodes_[index].first = begin;
    nodes_[index].count = end - begin;
    return 1;
  }
  int axis = 0;
  (max - min).maxCoeff(&axis);
  const int middle = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end,
                   [&](int a, int b) { return centroids_[a][axis] < centroids_[b][axis]; });
  const int first_child = static_cast<int>(nodes_.size());
  nodes_[index].first = first_child;
  nodes_[index].count = 0;
  nodes_.emplace_back();
  nodes_.emplace_back();
  const int left_depth = build(mesh, first_child, begin, middle);
  const int right_depth = build(mesh, first_child + 1, middle, end);
  const int depth = 1 + std::max(left_depth, right_depth);
  if (depth > kMaxDepth) throw std::length_error("triangle tree too deep");
  return depth;
}

TriangleAabbTree::Nearest TriangleAabbTree::nearest(const TriangleMesh& mesh,
                                                    const Eigen::Vector3d& p) const {
  Nearest best;
  best.squared_distance = std::numeric_limits<double>::infinity();
  std::array<int, kMaxDepth + 1> stack;
  int size = 0;
  stack[size++] = 0;
  while (size > 0) {
    const Node& node = nodes_[stack[--size]];
    if (squaredDistanceToBox(p, node.min, node.max) >= best.squared_distance) continue;
    if (node.count > 0) {
      for (int k = node.first; k < node.first + node.count; ++k) {
        const Eigen::Vector3i& t = mesh.triangles[order_[k]];
        const TriangleClosestPoint closest = closestPointOnTriangle(
            p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
        const double squared = (p - closest.point).squaredNorm();
        if (squared < best.squared_distance) best = {order_[k], closest, squared};
      }
      continue;
    }
    // The nearer child goes on top, so that it is searched first and prunes the other.
    const Node& left = nodes_[node.first];
    const Node& right = nodes_[node.first + 1];
    const bool left_nearer = squaredDistanceToBox(p, left.min, left.max) <=
                             squaredDistanceToBox(p, right.min, right.max);
    stack[size++] = left_nearer ? node.first + 1 : node.first;
    stack[size++] = left_nearer ? node.first : node.first + 1;
  }
  return best;
}

void TriangleAabbTree::trianglesNear(const Eigen::Vector3d& min, const Eigen::Vector3d& max,
                                     std::vector<int>& found) const {
  if (nodes_.empty()) return;
  std::array<int, kMaxDepth + 1> stack;
  int size = 0;
  stack[size++] = 0;
  while (size > 0) {
    const Node& node = nodes_[stack[--size]];
    if ((node.min.array() > max.array()).any() || (min.array() > node.max.array()).any()) continue;
    if (node.count > 0) {
      found.insert(found.end(), order_.begin() + node.first,
                   order_.begin() + node.first + node.count);
      continue;
    }
    stack[size++] = node.first;
    stack[size++] = node.first + 1;
  }
}

}  // namespace deformable_sim::core
