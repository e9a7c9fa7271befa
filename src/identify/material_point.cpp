#include "deformable_sim/identify/material_point.h"

#include <Eigen/LU>

#include "deformable_sim/core/elements/cell.h"

namespace deformable_sim::identify {

namespace {

std::optional<MaterialPoint> inTetrahedron(const core::Mesh& mesh, const core::Tetrahedron& tet,
                                           const Eigen::Vector3d& at, double slack) {
  const std::vector<Eigen::Vector3d>& x = mesh.positions;
  Eigen::Matrix3d edges;
  for (int k = 0; k < 3; ++k) edges.col(k) = x[tet[k + 1]] - x[tet[0]];
  if (std::abs(edges.determinant()) <= 0.0) return std::nullopt;
  const Eigen::Vector3d b = edges.inverse() * (at - x[tet[0]]);
  const double w0 = 1.0 - b.sum();
  const double size = edges.colwise().norm().maxCoeff();
  if (b.minCoeff() < -slack / size || w0 < -slack / size) return std::nullopt;
  return MaterialPoint{{tet[0], tet[1], tet[2], tet[3]}, {w0, b.x(), b.y(), b.z()}};
}

// Natural coordinates of `at` by Newton's method on x(xi) = sum N_i(xi) x_i.
std::optional<MaterialPoint> inCell(const core::Mesh& mesh, const core::Cell& cell,
                                    const Eigen::Vector3d& at, double slack) {
  const core::CellVectors corners = core::cellCorners(cell, mesh.positions);
  Eigen::Vector3d xi = core::naturalCentre(cell.type);
  core::ShapeValues shape;
  for (int iteration = 0; iteration < 20; ++iteration) {
    shape = core::shapeFunctions(cell.type, xi);
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    Eigen::Matrix3d jacobian = Eigen::Matrix3d::Zero();
    for (int i = 0; i < cell.size(); ++i) {
      x += shape.values[i] * corners[i];
      jacobian += corners[i] * shape.gradients[i].transpose();
    }
    if (std::abs(jacobian.determinant()) <= 0.0) return std::nullopt;
    const Eigen::Vector3d step = jacobian.inverse() * (at - x);
    xi += step;
    if (step.norm() < 1.0e-12) break;
  }
  shape = core::shapeFunctions(cell.type, xi);
  MaterialPoint point;
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int i = 0; i < cell.size(); ++i) {
    // Inside, every shape function is >= 0 (up to the slack, relative to the cell's size).
    if (shape.values[i] < -1.0e-6) return std::nullopt;
    point.nodes.push_back(cell.nodes[i]);
    point.weights.push_back(shape.values[i]);
    x += shape.values[i] * corners[i];
  }
  if ((x - at).norm() > slack) return std::nullopt;
  return point;
}

}  // namespace

Eigen::Vector3d MaterialPoint::position(const Eigen::VectorXd& positions) const {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < nodes.size(); ++k)
    x += weights[k] * positions.segment<3>(3 * nodes[k]);
  return x;
}

std::optional<MaterialPoint> findMaterialPoint(const core::Mesh& mesh, const Eigen::Vector3d& at,
                                               double tolerance) {
  for (const core::Tetrahedron& tet : mesh.tetrahedra) {
    if (auto point = inTetrahedron(mesh, tet, at, tolerance)) return point;
  }
  for (const core::Cell& cell : mesh.cells) {
    if (auto point = inCell(mesh, cell, at, tolerance)) return point;
  }
  return std::nullopt;
}

}  // namespace deformable_sim::identify
