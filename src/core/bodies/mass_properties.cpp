#include "deformable_sim/core/bodies/mass_properties.h"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "deformable_sim/core/elements/cell.h"

namespace deformable_sim::core {

MassProperties massProperties(const Mesh& mesh, double density) {
  // Moments about the first node, shifted to the centre at the end (less cancellation than about
  // the origin for a mesh far from it).
  const Eigen::Vector3d origin =
      mesh.positions.empty() ? Eigen::Vector3d::Zero() : mesh.positions.front();
  double volume = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();   // integral of X dV
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();  // integral of X X^T dV
  for (const Tetrahedron& t : mesh.tetrahedra) {
    std::array<Eigen::Vector3d, 4> p;
    for (int k = 0; k < 4; ++k) p[k] = mesh.positions[t[k]] - origin;
    const double v = (p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0]) / 6.0;
    const Eigen::Vector3d sum = p[0] + p[1] + p[2] + p[3];
    Eigen::Matrix3d outer = sum * sum.transpose();
    for (const Eigen::Vector3d& q : p) outer += q * q.transpose();
    volume += v;
    first += v / 4.0 * sum;
    second += v / 20.0 * outer;
  }
  for (size_t c = 0; c < mesh.cells.size(); ++c) {
    const Cell& cell = mesh.cells[c];
    for (const QuadraturePoint& q : materialQuadrature(cell.type, mesh.cellOctants(c))) {
      const ShapeValues shape = shapeFunctions(cell.type, q.xi);
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      Eigen::Matrix3d jacobian = Eigen::Matrix3d::Zero();  // dX/dxi
      for (int k = 0; k < cell.size(); ++k) {
        const Eigen::Vector3d corner = mesh.positions[cell.nodes[k]] - origin;
        x += shape.values[k] * corner;
        jacobian += corner * shape.gradients[k].transpose();
      }
      const double dv = q.weight * jacobian.determinant();
      volume += dv;
      first += dv * x;
      second += dv * x * x.transpose();
    }
  }
  MassProperties properties;
  properties.volume = volume;
  properties.mass = density * volume;
  if (volume > 0.0) {
    const Eigen::Vector3d centre = first / volume;
    properties.centre = origin + centre;
    properties.second_moment = density * (second - volume * centre * centre.transpose());
  }
  return properties;
}

}  // namespace deformable_sim::core
