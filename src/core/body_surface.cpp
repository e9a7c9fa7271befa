#include "deformable_sim/core/body_surface.h"

#include <algorithm>
#include <limits>

namespace deformable_sim::core {

namespace {

Box3 triangleBox(const Eigen::VectorXd& x, const Triangle& t) {
  Box3 box;
  for (int k = 0; k < 3; ++k) box.extend(Eigen::Vector3d(x.segment<3>(3 * t[k])));
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
    : triangles_(extractSurface(mesh)), start_(positions), boxes_(triangles_.size()) {
  Box3 rest;
  for (const Eigen::Vector3d& p : mesh.positions) rest.extend(p);
  size_ = mesh.positions.empty() ? 0.0 : rest.diagonal().norm();
  shortest_edge_ = std::numeric_limits<double>::infinity();
  for (const Triangle& t : triangles_) {
    for (int k = 0; k < 3; ++k) {
      nodes_.push_back(t[k]);
      const double edge = (mesh.positions[t[k]] - mesh.positions[t[(k + 1) % 3]]).norm();
      shortest_edge_ = std::min(shortest_edge_, edge);
    }
  }
  std::sort(nodes_.begin(), nodes_.end());
  nodes_.erase(std::unique(nodes_.begin(), nodes_.end()), nodes_.end());
  for (size_t k = 0; k < triangles_.size(); ++k) boxes_[k] = triangleBox(positions, triangles_[k]);
  tree_.build(boxes_);
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

void BodySurface::sweep(const Eigen::VectorXd& positions, double margin) {
  const Eigen::Vector3d widen = Eigen::Vector3d::Constant(margin);
  for (size_t k = 0; k < triangles_.size(); ++k) {
    Box3 box = triangleBox(start_, triangles_[k]).extend(triangleBox(positions, triangles_[k]));
    boxes_[k] = Box3(box.min() - widen, box.max() + widen);
  }
  tree_.refit(boxes_);
}

bool BodySurface::adjacent(int a, int b) const {
  if (offsets_.empty()) return a == b;
  return std::binary_search(neighbours_.begin() + offsets_[a],
                            neighbours_.begin() + offsets_[a + 1], b);
}

}  // namespace deformable_sim::core
