#include "deformable_sim/core/contact/body_surface.h"

#include <algorithm>
#include <limits>
#include <map>
#include <utility>

namespace deformable_sim::core {

namespace {

template <class Corners>
Box3 boxOf(const Eigen::VectorXd& x, const Corners& corners) {
  Box3 box;
  for (int i : corners) box.extend(Eigen::Vector3d(x.segment<3>(3 * i)));
  return box;
}

/// Every element's node list, tetrahedra and cells alike.
template <class Visit>
void forEachElement(const Mesh& mesh, Visit&& visit) {
  for (const Tetrahedron& t : mesh.tetrahedra) visit(t.data(), 4);
  for (const Cell& c : mesh.cells) visit(c.nodes.data(), c.size());
}

}  // namespace

BodySurface::BodySurface(const Mesh& mesh, const Eigen::VectorXd& positions, bool with_neighbours)
    : triangles_(extractSurface(mesh)), start_(positions), corners_now_(positions) {
  build(mesh.positions, positions);
  if (!with_neighbours) return;
  std::vector<std::vector<int>> lists(mesh.numNodes());
  forEachElement(mesh, [&](const int* nodes, int count) {
    for (int a = 0; a < count; ++a) {
      for (int b = 0; b < count; ++b) lists[nodes[a]].push_back(nodes[b]);
    }
  });
  offsets_.push_back(0);
  for (std::vector<int>& list : lists) {
    list.push_back(static_cast<int>(offsets_.size()) - 1);  // the node itself
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    neighbours_.insert(neighbours_.end(), list.begin(), list.end());
    offsets_.push_back(static_cast<int>(neighbours_.size()));
  }
}

BodySurface::BodySurface(const EmbeddedSurface& surface, const Eigen::VectorXd& positions)
    : start_(positions), embedded_(true), vertices_(surface.numVertices()) {
  for (const Eigen::Vector3i& t : surface.triangles()) triangles_.push_back({t[0], t[1], t[2]});
  for (int v = 0; v < surface.numVertices(); ++v) vertices_[v] = vertexPoint(surface, v);
  corner_start_.resize(3 * surface.numVertices());
  placeCorners(positions, corner_start_);
  corners_now_ = corner_start_;
  build(surface.restPositions(), corner_start_);
}

void BodySurface::build(const std::vector<Eigen::Vector3d>& rest, const Eigen::VectorXd& corners) {
  Box3 box;
  for (const Eigen::Vector3d& p : rest) box.extend(p);
  size_ = rest.empty() ? 0.0 : box.diagonal().norm();
  shortest_edge_ = std::numeric_limits<double>::infinity();
  for (const Triangle& t : triangles_) {
    for (int k = 0; k < 3; ++k) {
      nodes_.push_back(t[k]);
      shortest_edge_ = std::min(shortest_edge_, (rest[t[k]] - rest[t[(k + 1) % 3]]).norm());
    }
  }
  std::sort(nodes_.begin(), nodes_.end());
  nodes_.erase(std::unique(nodes_.begin(), nodes_.end()), nodes_.end());
  // A counting sort of the triangles by corner.
  triangles_at_.assign(rest.size() + 1, 0);
  for (const Triangle& t : triangles_) {
    for (int c : t) ++triangles_at_[c + 1];
  }
  for (size_t c = 0; c < rest.size(); ++c) triangles_at_[c + 1] += triangles_at_[c];
  corner_triangles_.resize(triangles_at_.back());
  std::vector<int> placed(triangles_at_.begin(), triangles_at_.end() - 1);
  for (size_t k = 0; k < triangles_.size(); ++k) {
    for (int c : triangles_[k]) corner_triangles_[placed[c]++] = static_cast<int>(k);
  }
  for (const Triangle& t : triangles_) boxes_.push_back(boxOf(corners, t));
  tree_.build(boxes_);
  findEdges(rest);
  for (const SurfaceEdge& edge : edges_) edge_boxes_.push_back(boxOf(corners, edge.nodes));
  edge_tree_.build(edge_boxes_);
}

void BodySurface::placeCorners(const Eigen::VectorXd& positions, Eigen::VectorXd& corners) const {
  for (size_t v = 0; v < vertices_.size(); ++v) {
    const SurfacePoint& vertex = vertices_[v];
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int k = 0; k < vertex.count; ++k) {
      x += vertex.weights[k] * positions.segment<3>(3 * vertex.nodes[k]);
    }
    corners.segment<3>(3 * v) = x;
  }
}

SurfacePoint BodySurface::corner(int c) const {
  if (embedded_) return vertices_[c];
  SurfacePoint point;
  point.nodes[0] = c;
  point.weights[0] = 1.0;
  point.count = 1;
  return point;
}

SurfacePoint BodySurface::trianglePoint(const Triangle& t,
                                        const std::array<double, 3>& weights) const {
  SurfacePoint point;
  for (int k = 0; k < 3; ++k) point.add(corner(t[k]), weights[k]);
  return point;
}

SurfacePoint BodySurface::edgePoint(const SurfaceEdge& edge, double s) const {
  SurfacePoint point;
  point.add(corner(edge.nodes[0]), 1.0 - s);
  point.add(corner(edge.nodes[1]), s);
  return point;
}

void BodySurface::setStart(const Eigen::VectorXd& positions) {
  start_ = positions;
  if (embedded_) placeCorners(positions, corner_start_);
}

void BodySurface::findEdges(const std::vector<Eigen::Vector3d>& rest) {
  // (lower node, higher node) -> the triangles that have that edge
  std::map<std::pair<int, int>, std::vector<int>> sharing;
  folds_.assign(triangles_.size(), {false, false, false});
  for (size_t t = 0; t < triangles_.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = triangles_[t][k], b = triangles_[t][(k + 1) % 3];
      sharing[{std::min(a, b), std::max(a, b)}].push_back(static_cast<int>(t));
    }
  }
  const auto normal = [&](int t) {
    const Triangle& c = triangles_[t];
    return Eigen::Vector3d((rest[c[1]] - rest[c[0]]).cross(rest[c[2]] - rest[c[0]]).normalized());
  };
  for (const auto& [nodes, triangles] : sharing) {
    if (triangles.size() != 2) continue;  // not a simple ridge: left to nodes and triangles
    const Eigen::Vector3d n0 = normal(triangles[0]), n1 = normal(triangles[1]);
    if (!(n0.dot(n1) < kFeatureCosine)) continue;  // flat (or degenerate)
    // Convex when the second triangle's far corner lies behind the first one's plane.
    const Triangle& second = triangles_[triangles[1]];
    int apex = second[0];
    for (int k : second) apex = (k != nodes.first && k != nodes.second) ? k : apex;
    if (!(n0.dot(rest[apex] - rest[nodes.first]) < 0.0)) continue;
    edges_.push_back({{nodes.first, nodes.second}, {triangles[0], triangles[1]}});
    for (int t : triangles) {
      for (int k = 0; k < 3; ++k) {
        const int a = triangles_[t][k], b = triangles_[t][(k + 1) % 3];
        if (std::min(a, b) == nodes.first && std::max(a, b) == nodes.second) folds_[t][k] = true;
      }
    }
  }
}

void BodySurface::sweep(const Eigen::VectorXd& positions, double margin) {
  if (embedded_) {
    placeCorners(positions, corners_now_);
  } else {
    corners_now_ = positions;  // sized when built: no allocation
  }
  const Eigen::VectorXd& now = corners_now_;
  const Eigen::VectorXd& start = this->start();
  const Eigen::Vector3d widen = Eigen::Vector3d::Constant(margin);
  for (size_t k = 0; k < triangles_.size(); ++k) {
    const Box3 box = boxOf(start, triangles_[k]).extend(boxOf(now, triangles_[k]));
    boxes_[k] = Box3(box.min() - widen, box.max() + widen);
  }
  tree_.refit(boxes_);
  for (size_t k = 0; k < edges_.size(); ++k) {
    const Box3 box = boxOf(start, edges_[k].nodes).extend(boxOf(now, edges_[k].nodes));
    edge_boxes_[k] = Box3(box.min() - widen, box.max() + widen);
  }
  edge_tree_.refit(edge_boxes_);
}

Eigen::Vector3d BodySurface::outwardAt(int c) const {
  Eigen::Vector3d outward = Eigen::Vector3d::Zero();
  for (int k = triangles_at_[c]; k < triangles_at_[c + 1]; ++k) {
    const Triangle& t = triangles_[corner_triangles_[k]];
    outward += (now(t[1]) - now(t[0])).cross(now(t[2]) - now(t[0]));
  }
  return outward;
}

bool BodySurface::adjacent(int a, int b) const {
  if (embedded_) {  // vertices whose cells share a node
    const SurfacePoint &p = vertices_[a], &q = vertices_[b];
    for (int i = 0; i < p.count; ++i) {
      for (int j = 0; j < q.count; ++j) {
        if (p.nodes[i] == q.nodes[j]) return true;
      }
    }
    return a == b;
  }
  if (offsets_.empty()) return a == b;
  return std::binary_search(neighbours_.begin() + offsets_[a],
                            neighbours_.begin() + offsets_[a + 1], b);
}

}  // namespace deformable_sim::core
