// A mesh's elements under a hyperelastic law (materials/neo_hookean.h), in the total Lagrangian
// form: at each integration point the deformation gradient F = sum_i x_i (grad N_i)^T from the
// rest gradients of the shape functions, the energy sum_q V_q W(F_q), the nodal forces
// f_i = -sum_q V_q P(F_q) grad N_i and the tangent K = d^2 E / dx^2. Tetrahedra take one point
// (CalculiX's C3D4), the other cells their full Gauss rule (C3D8 for hexahedra; cell.h), of their
// material where a cell is partly filled.
//
// Where the energy is not convex (compression past a buckling load, elements near inversion), K
// is indefinite; a step that needs a positive semi-definite matrix asks for each element's block
// projected onto its non-negative eigenvalues (the convention of Teran et al. 2005 and Drake).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <vector>

#include "deformable_sim/core/elements/mesh.h"
#include "deformable_sim/core/materials/neo_hookean.h"

namespace deformable_sim::core {

class HyperelasticElements {
 public:
  static constexpr int kMaxNodes = 8;
  /// An element's matrix, 3 x 3 blocks of its nodes in its order; never on the heap.
  using ElementMatrix =
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3 * kMaxNodes, 3 * kMaxNodes>;

  /// Rest data for every element of `mesh`. Throws std::invalid_argument naming the element
  /// when one is inverted or flat at an integration point.
  HyperelasticElements(const Mesh& mesh, const NeoHookean& law);

  int numNodes() const { return num_nodes_; }
  double volume() const { return volume_; }  ///< the rest volume of all elements, m^3
  const NeoHookean& law() const { return law_; }
  void setLaw(const NeoHookean& law) { law_ = law; }

  /// The elastic energy at node positions x (3 per node, node-major), J.
  double energy(const Eigen::VectorXd& x) const;
  /// Adds the elastic forces -dE/dx at x to `forces`, N.
  void addForces(const Eigen::VectorXd& x, Eigen::VectorXd& forces) const;
  /// The tangent d^2 E / dx^2 at x (3n x 3n, symmetric), each element's block projected onto its
  /// non-negative eigenvalues when `projected`.
  Eigen::SparseMatrix<double> tangent(const Eigen::VectorXd& x, bool projected) const;

  /// Element by element (the mesh's tetrahedra, then its cells), for an assembly of one's own.
  int numElements() const { return static_cast<int>(elements_.size()); }
  const std::array<int, kMaxNodes>& elementNodes(int e) const { return elements_[e].nodes; }
  int elementSize(int e) const { return elements_[e].size; }
  /// Element e's energy at x, J; `inverted` gains its integration points with det F <= 0.
  double elementEnergy(int e, const Eigen::VectorXd& x, int& inverted) const;
  /// F at element e's first integration point (its only one for a tetrahedron).
  Eigen::Matrix3d elementDeformationGradient(int e, const Eigen::VectorXd& x) const;
  /// An element's vector, 3 entries per node in its order; never on the heap.
  using ElementVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3 * kMaxNodes, 1>;
  /// Element e's forces (3 per node, its order), N.
  ElementVector elementForces(int e, const Eigen::VectorXd& x) const;
  /// Element e's energy (J, returned) and forces (N) at x in one pass; `inverted` as above.
  double elementEnergyAndForces(int e, const Eigen::VectorXd& x, int& inverted,
                                ElementVector& forces) const;
  /// Element e's tangent block, projected onto its non-negative eigenvalues when `projected`.
  ElementMatrix elementTangent(int e, const Eigen::VectorXd& x, bool projected) const;

 private:
  struct Point {
    std::array<Eigen::Vector3d, kMaxNodes> gradients;  ///< grad N_i at rest, 1/m
    double volume;                                     ///< the rest volume it stands for, m^3
  };
  struct Element {
    std::array<int, kMaxNodes> nodes{};
    int size = 0;
    int first_point = 0, points = 0;
  };

  void addElement(const std::array<int, kMaxNodes>& nodes, int size,
                  const std::vector<Point>& points);
  /// A cell's integration points (`index`: its number, for the error where it is inverted).
  static std::vector<Point> cellPoints(const Cell& cell, const std::vector<Eigen::Vector3d>& rest,
                                       const OctantFractions* fractions, size_t index);
  /// F at a point of an element for positions x.
  Eigen::Matrix3d deformationGradient(const Element& element, const Point& point,
                                      const Eigen::VectorXd& x) const;

  NeoHookean law_;
  int num_nodes_ = 0;
  double volume_ = 0.0;
  std::vector<Element> elements_;
  std::vector<Point> points_;
};

}  // namespace deformable_sim::core
