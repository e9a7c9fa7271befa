#include "deformable_sim/core/selection.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace deformable_sim::core {

std::vector<int> selectNodes(const Mesh& mesh, const NodeSelection& selection) {
  std::vector<int> selected;
  switch (selection.kind) {
    case NodeSelection::Kind::kNodes:
      selected = nodeIndices(mesh, selection.node_numbers);
      break;
    case NodeSelection::Kind::kBox: {
      const Box& box = selection.box;
      if (!box.min.allFinite() || !box.max.allFinite() || (box.min.array() > box.max.array()).any()) {
        throw std::invalid_argument("box: min must not exceed max on any axis (and be finite)");
      }
      for (int i = 0; i < mesh.numNodes(); ++i) {
        const Eigen::Vector3d& p = mesh.positions[i];
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
        if ((mesh.positions[i] - sphere.center).norm() <= sphere.radius) selected.push_back(i);
      }
      break;
    }
  }
  std::sort(selected.begin(), selected.end());
  selected.erase(std::unique(selected.begin(), selected.end()), selected.end());
  return selected;
}

}  // namespace deformable_sim::core
