#include "deformable_sim/core/elements/loads.h"

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <stdexcept>

namespace deformable_sim::core {

namespace {

// Integrals of the bilinear shape functions over a quadrilateral (a, b, c, d), by 2x2 Gauss
// (exact for a planar quadrilateral); returns the area.
double quadShares(const std::array<Eigen::Vector3d, 4>& x, std::array<double, 4>& shares) {
  const double g = 1.0 / std::sqrt(3.0);
  const double corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  shares.fill(0.0);
  double area = 0.0;
  for (double s : {-g, g}) {
    for (double t : {-g, g}) {
      Eigen::Vector3d dx_ds = Eigen::Vector3d::Zero(), dx_dt = Eigen::Vector3d::Zero();
      for (int k = 0; k < 4; ++k) {
        dx_ds += 0.25 * corner[k][0] * (1 + corner[k][1] * t) * x[k];
        dx_dt += 0.25 * corner[k][1] * (1 + corner[k][0] * s) * x[k];
      }
      const double da = dx_ds.cross(dx_dt).norm();
      for (int k = 0; k < 4; ++k) {
        shares[k] += 0.25 * (1 + corner[k][0] * s) * (1 + corner[k][1] * t) * da;
      }
      area += da;
    }
  }
  return area;
}

}  // namespace

double addTractionLoad(const Mesh& mesh, const std::vector<Face>& boundary,
                       const std::vector<int>& selected, const Eigen::Vector3d& traction,
                       Eigen::VectorXd& f) {
  std::vector<bool> in_selection(mesh.numNodes(), false);
  for (int i : selected) in_selection[i] = true;
  double area = 0.0;
  for (const Face& face : boundary) {
    const int size = face.size();
    bool loaded = true;
    for (int k = 0; k < size; ++k) loaded = loaded && in_selection[face.nodes[k]];
    if (!loaded) continue;
    if (size == 3) {
      const Eigen::Vector3d& a = mesh.positions[face.nodes[0]];
      const double face_area =
          0.5 * (mesh.positions[face.nodes[1]] - a).cross(mesh.positions[face.nodes[2]] - a).norm();
      for (int k = 0; k < 3; ++k) f.segment<3>(3 * face.nodes[k]) += (face_area / 3.0) * traction;
      area += face_area;
    } else {
      std::array<Eigen::Vector3d, 4> x;
      for (int k = 0; k < 4; ++k) x[k] = mesh.positions[face.nodes[k]];
      std::array<double, 4> shares;
      area += quadShares(x, shares);
      for (int k = 0; k < 4; ++k) f.segment<3>(3 * face.nodes[k]) += shares[k] * traction;
    }
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
