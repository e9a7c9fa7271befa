#include "deformable_sim/core/elements/selection.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace deformable_sim::core {

namespace {

template <typename Position>
std::vector<int> select(const Mesh& mesh, const NodeSelection& selection, Position position) {
  std::vector<int> selected;
  switch (selection.kind) {
    case NodeSelection::Kind::kNodes:
      selected = nodeIndices(mesh, selection.node_numbers);
      break;
    case NodeSelection::Kind::kBox: {
      const Box& box = selection.box;
      if (!box.min.allFinite() || !box.max.allFinite() ||
          (box.min.array() > box.max.array()).any()) {
        throw std::invalid_argument("box: min must not exceed max on any axis (and be finite)");
      }
      for (int i = 0; i < mesh.numNodes(); ++i) {
        const Eigen::Vector3d p = position(i);
        if ((p.array() >= box.min.array()).all() && (p.array() <= box.max.array()).all()) {
          selected.push_back(i);
        }
      }
      break;
    }
    case NodeSelection::Kind::kSphere: {
      const Sphere& sphere = selection.sphere;
      if (!(sphere.radius >= 0.0) || !std::isfinite(sphere.radius) || !sphere.center.allFinite()) {
        throw std::invalid_argument("sphere: radius must be finite and >= 0, centre finite");
      }
      for (int i = 0; i < mesh.numNodes(); ++i) {
        if ((position(i) - sphere.center).norm() <= sphere.radius) selected.push_back(i);
      }
      break;
    }
  }
  std::sort(selected.begin(), selected.end());
  selected.erase(std::unique(selected.begin(), selected.end()), selected.end());
  return selected;
}

}  // namespace

std::vector<int> selectNodes(const Mesh& mesh, const NodeSelection& selection) {
  return select(mesh, selection, [&](int i) { return mesh.positions[i]; });
}

std::vector<int> selectNodesAt(const Mesh& mesh, const Eigen::VectorXd& positions,
                               const NodeSelection& selection) {
  return select(mesh, selection,
                [&](int i) { return Eigen::Vector3d(positions.segment<3>(3 * i)); });
}

}  // namespace deformable_sim::core
