#include "deformable_sim/core/materials/hyperelastic_elements.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <sstream>
#include <stdexcept>

#include "deformable_sim/core/elements/cell.h"
#include "deformable_sim/core/elements/tetrahedron.h"

namespace deformable_sim::core {

HyperelasticElements::HyperelasticElements(const Mesh& mesh, const NeoHookean& law)
    : law_(law), num_nodes_(mesh.numNodes()) {
  for (const Tetrahedron& t : mesh.tetrahedra) {
    const std::array<Eigen::Vector3d, 4> corners = {mesh.positions[t[0]], mesh.positions[t[1]],
                                                    mesh.positions[t[2]], mesh.positions[t[3]]};
    const TetrahedronRest rest = computeTetrahedronRest(corners);
    if (!(rest.volume > 0.0)) {
      std::ostringstream message;
      message << "tetrahedron " << elements_.size() << " has no positive volume";
      throw std::invalid_argument(message.str());
    }
    Point point{{}, rest.volume};
    point.gradients.fill(Eigen::Vector3d::Zero());
    for (int k = 0; k < 4; ++k) point.gradients[k] = rest.gradients[k];
    addElement({t[0], t[1], t[2], t[3]}, 4, {point});
  }
  for (size_t c = 0; c < mesh.cells.size(); ++c) {
    const Cell& cell = mesh.cells[c];
    addElement(cell.nodes, cell.size(), cellPoints(cell, mesh.positions, mesh.cellOctants(c), c));
  }
}

void HyperelasticElements::addElement(const std::array<int, kMaxNodes>& nodes, int size,
                                      const std::vector<Point>& points) {
  Element element;
  element.nodes = nodes;
  element.size = size;
  element.first_point = static_cast<int>(points_.size());
  element.points = static_cast<int>(points.size());
  points_.insert(points_.end(), points.begin(), points.end());
  for (const Point& point : points) volume_ += point.volume;
  elements_.push_back(element);
}

Eigen::Matrix3d HyperelasticElements::deformationGradient(const Element& element,
                                                          const Point& point,
                                                          const Eigen::VectorXd& x) const {
  Eigen::Matrix3d f = Eigen::Matrix3d::Zero();
  for (int k = 0; k < element.size; ++k) {
    f.noalias() += x.segment<3>(3 * element.nodes[k]) * point.gradients[k].transpose();
  }
  return f;
}

double HyperelasticElements::elementEnergy(int e, const Eigen::VectorXd& x, int& inverted) const {
  const Element& element = elements_[e];
  double sum = 0.0;
  for (int q = element.first_point; q < element.first_point + element.points; ++q) {
    const Eigen::Matrix3d f = deformationGradient(element, points_[q], x);
    inverted += !(f.determinant() > 0.0);
    sum += points_[q].volume * law_.energyDensity(f);
  }
  return sum;
}

Eigen::Matrix3d HyperelasticElements::elementDeformationGradient(int e,
                                                                 const Eigen::VectorXd& x) const {
  return deformationGradient(elements_[e], points_[elements_[e].first_point], x);
}

HyperelasticElements::ElementVector HyperelasticElements::elementForces(
    int e, const Eigen::VectorXd& x) const {
  ElementVector forces;
  int inverted = 0;
  elementEnergyAndForces(e, x, inverted, forces);
  return forces;
}

double HyperelasticElements::elementEnergyAndForces(int e, const Eigen::VectorXd& x, int& inverted,
                                                    ElementVector& forces) const {
  const Element& element = elements_[e];
  forces.setZero(3 * element.size);
  double sum = 0.0;
  for (int q = element.first_point; q < element.first_point + element.points; ++q) {
    const Point& point = points_[q];
    const Eigen::Matrix3d f = deformationGradient(element, point, x);
    inverted += !(f.determinant() > 0.0);
    const NeoHookean::EnergyAndStress w = law_.energyAndStress(f);
    sum += point.volume * w.energy;
    for (int k = 0; k < element.size; ++k) {
      forces.segment<3>(3 * k).noalias() -= point.volume * (w.piola * point.gradients[k]);
    }
  }
  return sum;
}

double HyperelasticElements::energy(const Eigen::VectorXd& x) const {
  double sum = 0.0;
  int inverted = 0;
  for (int e = 0; e < numElements(); ++e) sum += elementEnergy(e, x, inverted);
  return sum;
}

void HyperelasticElements::addForces(const Eigen::VectorXd& x, Eigen::VectorXd& forces) const {
  for (int e = 0; e < numElements(); ++e) {
    const Element& element = elements_[e];
    const auto f = elementForces(e, x);
    for (int k = 0; k < element.size; ++k)
      forces.segment<3>(3 * element.nodes[k]) += f.segment<3>(3 * k);
  }
}

HyperelasticElements::ElementMatrix HyperelasticElements::elementTangent(int e,
                                                                         const Eigen::VectorXd& x,
                                                                         bool projected) const {
  // vec(F) = B x_e with B(3 c + r, 3 k + r) = (grad N_k)_c, so K_e = sum_q V_q B^T (dP/dF) B.
  const Element& element = elements_[e];
  const int n = 3 * element.size;
  ElementMatrix k = ElementMatrix::Zero(n, n);
  Eigen::Matrix<double, 9, Eigen::Dynamic, 0, 9, 3 * kMaxNodes> b(9, n);
  for (int q = element.first_point; q < element.first_point + element.points; ++q) {
    const Point& point = points_[q];
    b.setZero();
    for (int node = 0; node < element.size; ++node) {
      for (int c = 0; c < 3; ++c) {
        for (int r = 0; r < 3; ++r) b(3 * c + r, 3 * node + r) = point.gradients[node][c];
      }
    }
    const Eigen::Matrix<double, 9, 9> a =
        law_.firstPiolaDerivative(deformationGradient(element, point, x));
    k.noalias() += point.volume * (b.transpose() * a * b);
  }
  k = 0.5 * (k + k.transpose()).eval();  // symmetric to round-off; exactly so for the projection
  if (!projected) return k;
  const Eigen::SelfAdjointEigenSolver<ElementMatrix> eigen(k);
  return eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0.0).asDiagonal() *
         eigen.eigenvectors().transpose();
}

Eigen::SparseMatrix<double> HyperelasticElements::tangent(const Eigen::VectorXd& x,
                                                          bool projected) const {
  std::vector<Eigen::Triplet<double>> entries;
  for (int e = 0; e < numElements(); ++e) {
    const Element& element = elements_[e];
    const ElementMatrix k = elementTangent(e, x, projected);
    for (int i = 0; i < element.size; ++i) {
      for (int j = 0; j < element.size; ++j) {
        for (int r = 0; r < 3; ++r) {
          for (int s = 0; s < 3; ++s) {
            entries.emplace_back(3 * element.nodes[i] + r, 3 * element.nodes[j] + s,
                                 k(3 * i + r, 3 * j + s));
          }
        }
      }
    }
  }
  Eigen::SparseMatrix<double> matrix(3 * num_nodes_, 3 * num_nodes_);
  matrix.setFromTriplets(entries.begin(), entries.end());
  return matrix;
}

std::vector<HyperelasticElements::Point> HyperelasticElements::cellPoints(
    const Cell& cell, const std::vector<Eigen::Vector3d>& rest, const OctantFractions* fractions,
    size_t index) {
  const CellVectors corners = cellCorners(cell, rest);
  std::vector<Point> points;
  for (const QuadraturePoint& q : materialQuadrature(cell.type, fractions)) {
    const ShapeValues shape = shapeFunctions(cell.type, q.xi);
    Eigen::Matrix3d jacobian = Eigen::Matrix3d::Zero();  // dX / dxi
    for (int k = 0; k < cell.size(); ++k) jacobian += corners[k] * shape.gradients[k].transpose();
    const double det = jacobian.determinant();
    if (!(det > 0.0)) {
      std::ostringstream message;
      message << "cell " << index << " is inverted or flat at an integration point";
      throw std::invalid_argument(message.str());
    }
    Point point{{}, q.weight * det};
    point.gradients.fill(Eigen::Vector3d::Zero());
    const Eigen::Matrix3d inverse_transpose = jacobian.inverse().transpose();
    for (int k = 0; k < cell.size(); ++k)
      point.gradients[k] = inverse_transpose * shape.gradients[k];
    points.push_back(point);
  }
  return points;
}

}  // namespace deformable_sim::core
