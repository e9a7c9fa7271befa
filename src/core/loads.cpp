#include "deformable_sim/core/loads.h"

#include <Eigen/Geometry>
#include <stdexcept>

namespace deformable_sim::core {

double addTractionLoad(const Mesh& mesh, const std::vector<Triangle>& surface,
                       const std::vector<int>& selected, const Eigen::Vector3d& traction,
                       Eigen::VectorXd& f) {
  std::vector<bool> in_selection(mesh.numNodes(), false);
  for (int i : selected) in_selection[i] = true;
  double area = 0.0;
  for (const Triangle& tri : surface) {
    if (!(in_selection[tri[0]] && in_selection[tri[1]] && in_selection[tri[2]])) continue;
    const Eigen::Vector3d& a = mesh.positions[tri[0]];
    const double face_area =
        0.5 * (mesh.positions[tri[1]] - a).cross(mesh.positions[tri[2]] - a).norm();
    for (int i : tri) f.segment<3>(3 * i) += (face_area / 3.0) * traction;
    area += face_area;
  }
  return area;
}

void addTotalForce(const std::vector<int>& selected, const Eigen::Vector3d& total,
                   Eigen::VectorXd& f) {
  if (selected.empty()) throw std::invalid_argument("total_force: no node selected");
  const Eigen::Vector3d share = total / static_cast<double>(selected.size());
  for (int i : selected) f.segment<3>(3 * i) += share;
}

}  // namespace deformable_sim::core
