#include "deformable_sim/core/geometry/winding_number.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>

namespace deformable_sim::core {

namespace {

constexpr int kLeafSize = 8;
/// A median split halves the triangles: the depth stays near log2(n), far below this.
constexpr int kMaxDepth = 128;
constexpr double kFourPi = 4.0 * M_PI;

}  // namespace

double solidAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  const Eigen::Vector3d& q) {
  // tan(omega / 2) = a.(b x c) / (|a||b||c| + (a.b)|c| + (a.c)|b| + (b.c)|a|), corners from q.
  const Eigen::Vector3d u = a - q, v = b - q, w = c - q;
  const double lu = u.norm(), lv = v.norm(), lw = w.norm();
  const double numerator = u.dot(v.cross(w));
  const double denominator = lu * lv * lw + u.dot(v) * lw + u.dot(w) * lv + v.dot(w) * lu;
  return 2.0 * std::atan2(numerator, denominator);
}

double exactWindingNumber(const TriangleMesh& surface, const Eigen::Vector3d& q) {
  double sum = 0.0;
  for (const Eigen::Vector3i& t : surface.triangles) {
    sum += solidAngle(surface.vertices[t[0]], surface.vertices[t[1]], surface.vertices[t[2]], q);
  }
  return sum / kFourPi;
}

WindingNumber::WindingNumber(const TriangleMesh& surface) : surface_(surface) {
  const int n = static_cast<int>(surface.triangles.size());
  order_.resize(n);
  centroids_.resize(n);
  for (int t = 0; t < n; ++t) {
    order_[t] = t;
    const Eigen::Vector3i& tri = surface.triangles[t];
    centroids_[t] =
        (surface.vertices[tri[0]] + surface.vertices[tri[1]] + surface.vertices[tri[2]]) / 3.0;
  }
  nodes_.reserve(2 * (n / kLeafSize + 1));
  nodes_.emplace_back();
  if (n > 0) build(0, n);
  centroids_.clear();
  centroids_.shrink_to_fit();
}

void WindingNumber::summarize(Node& node, int begin, int end) const {
  double area = 0.0;
  node.centre.setZero();
  node.area_normal.setZero();
  for (int k = begin; k < end; ++k) {
    const Eigen::Vector3i& t = surface_.triangles[order_[k]];
    const Eigen::Vector3d& a = surface_.vertices[t[0]];
    const Eigen::Vector3d normal =
        0.5 * (surface_.vertices[t[1]] - a).cross(surface_.vertices[t[2]] - a);
    node.area_normal += normal;
    area += normal.norm();
    node.centre += normal.norm() * centroids_[order_[k]];
  }
  // A group of degenerate triangles has no area: its plain centroid will do.
  if (area > 0.0) {
    node.centre /= area;
  } else {
    node.centre = centroids_[order_[begin]];
  }
  node.radius = 0.0;
  for (int k = begin; k < end; ++k) {
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d& p = surface_.vertices[surface_.triangles[order_[k]][c]];
      node.radius = std::max(node.radius, (p - node.centre).norm());
    }
  }
}

// Fills the last node of nodes_ with triangles order_[begin, end), then its subtree after it.
void WindingNumber::build(int begin, int end) {
  const int index = static_cast<int>(nodes_.size()) - 1;
  summarize(nodes_[index], begin, end);
  nodes_[index].first = begin;
  if (end - begin <= kLeafSize) {
    nodes_[index].count = end - begin;
    return;
  }
  Eigen::AlignedBox3d box;
  for (int k = begin; k < end; ++k) box.extend(centroids_[order_[k]]);
  int axis = 0;
  box.sizes().maxCoeff(&axis);
  const int middle = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end,
                   [&](int s, int t) { return centroids_[s][axis] < centroids_[t][axis]; });
  nodes_[index].left = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  build(begin, middle);
  nodes_[index].right = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  build(middle, end);
}

double WindingNumber::at(const Eigen::Vector3d& q) const {
  if (surface_.triangles.empty()) return 0.0;
  std::array<int, kMaxDepth> stack;
  int size = 0;
  stack[size++] = 0;
  double sum = 0.0;
  while (size > 0) {
    const Node& node = nodes_[stack[--size]];
    const Eigen::Vector3d to_centre = node.centre - q;
    const double distance = to_centre.norm();
    if (distance > kFarRatio * node.radius) {
      // A small patch of area A and normal n at distance r subtends A n . r / |r|^3.
      sum += node.area_normal.dot(to_centre) / (distance * distance * distance);
    } else if (node.left < 0) {
      for (int k = node.first; k < node.first + node.count; ++k) {
        const Eigen::Vector3i& t = surface_.triangles[order_[k]];
        sum += solidAngle(surface_.vertices[t[0]], surface_.vertices[t[1]], surface_.vertices[t[2]],
                          q);
      }
    } else {
      stack[size++] = node.left;
      stack[size++] = node.right;
    }
  }
  return sum / kFourPi;
}

}  // namespace deformable_sim::core
