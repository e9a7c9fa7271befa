// Warped-stiffness (corotational) elasticity of a tetrahedral mesh, after Müller et al. 2002 and
// OpenTissue's stiffness assembly: each element's rest stiffness Ke is rotated by the element's
// current rotation Re, giving
//   K'_ij = sum_e Re Ke_ij Re^T,   f0'_i = -sum_e Re sum_j Ke_ij x0_j,   f_elastic = -(K' x + f0').
// With Re = I (warping off) this is plain linear FEM.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "deformable_sim/core/elements/cell.h"
#include "deformable_sim/core/elements/elastic_model.h"
#include "deformable_sim/core/elements/material.h"
#include "deformable_sim/core/elements/mesh.h"
#include "deformable_sim/core/elements/tetrahedron.h"
#include "deformable_sim/core/solvers/block_sparse_matrix.h"

namespace deformable_sim::core {

class CorotationalElasticity : public ElasticModel {
 public:
  /// Validates the material (std::invalid_argument) and precomputes every element's rest data and
  /// its block indices in the global pattern.
  CorotationalElasticity(const Mesh& mesh, const LinearElasticMaterial& material);

  /// A new material (validated first) for the next update; the rest shape, the pattern and the
  /// block indices stay.
  void setMaterial(const LinearElasticMaterial& material) override;
  /// Linear elasticity is its own linearization: only warping follows the positions.
  bool followsPositions() const override { return false; }

  /// Sets the element rotations from positions x (3n): polar rotations of F when warping, the
  /// identity otherwise; then fills K' and f0' in place. Returns the number of inverted or flat
  /// elements (det F <= 0). Allocates nothing.
  int update(const Eigen::VectorXd& x, bool warping);

  /// What updateRotations found at x: its energy with the new rotations (the true one) and with
  /// those before.
  using RotationUpdate = ElasticModel::Update;
  /// The two halves of update(): the rotations from x, then K' and f0' from the rotations.
  RotationUpdate updateRotations(const Eigen::VectorXd& x);
  void assemble() override;
  Update linearizeAt(const Eigen::VectorXd& x) override { return updateRotations(x); }

  /// Threads for the element and row loops (1: none started). K' is assembled row by row on any
  /// count, every block summing its elements in element order, so the results are identical.
  void setThreads(int threads) override;

  double lambda() const { return lambda_; }  ///< Lame's first parameter, Pa
  double mu() const { return mu_; }          ///< shear modulus, Pa
  const BlockSparseMatrix& stiffness() const override { return stiffness_; }     ///< K', N/m
  const Eigen::VectorXd& forceOffset() const override { return force_offset_; }  ///< f0', N
  /// Per element, the tetrahedra first, then the cells.
  const std::vector<Eigen::Matrix3d>& rotations() const override { return rotations_; }
  /// A cell's at its centre, where its rotation is taken.
  Eigen::Matrix3d deformationGradient(int e, const Eigen::VectorXd& x) const override {
    return elementDeformationGradient(e, x);
  }
  const std::vector<TetrahedronRest>& restData() const { return rest_; }
  const CellRest& cellRestData(int c) const { return cells_[c].rest; }  ///< of Mesh::cells[c]

  /// f += -(K' x + f0') with the K' and f0' of the last update. `scratch` has size 3n.
  void addElasticForces(const Eigen::VectorXd& x, Eigen::VectorXd& f,
                        Eigen::VectorXd& scratch) const;

  /// Elastic energy with the rotations of the last update: sum_e 1/2 u_e^T Ke u_e with
  /// u_e,i = Re^T x_i - x0_i, J. The same sum on any thread count. Not for concurrent calls on
  /// one object (it sums into a buffer of the object).
  double elasticEnergy(const Eigen::VectorXd& x) const override;

 private:
  void setRestForces();
  /// Builds each node's list of (element, corner) pairs, for the row-by-row assembly.
  void listIncidences(int num_nodes);
  /// Each cell's rest stiffness and rest-force offset for the current material.
  void setCellStiffness();
  /// Row i of K' (its diagonal and upper blocks, and their transposes into the rows below) and of
  /// f0', from warped_. Rows are disjoint, so threads may take any of them at once.
  void assembleRowPortable(int i);
  void assembleRowAvx2(int i);  ///< the same with 4-wide vectors (other bits: FMA)
  void startRow(int i);         ///< zeroes row i's diagonal and upper blocks
  /// Stores row i of f0' and writes the transposes of its (summed) upper blocks below.
  void finishRow(int i, const Eigen::Vector3d& offset);
  void prefetchWarped(int e) const;
  /// Adds the warped cells to K' and f0'.
  void addCells();
  static CellVectors currentCorners(const Cell& cell, const Eigen::VectorXd& x);

  /// A pyramid, wedge or hexahedron: its stiffness is integrated numerically, so it is stored.
  struct CellElement {
    Cell cell;
    OctantFractions fractions = {1, 1, 1, 1, 1, 1, 1, 1};  ///< Mesh::cell_fractions
    CellRest rest;
    Eigen::MatrixXd stiffness;                                     ///< Ke (3n x 3n), N/m
    Eigen::VectorXd rest_forces;                                   ///< Ke x0, N
    std::array<int, kMaxCellNodes * kMaxCellNodes> block_index{};  ///< slot of (i, j) at n i + j
  };
  std::vector<CellElement> cells_;
  bool incompatible_modes_ = false;  ///< Mesh::incompatible_modes

  std::vector<Tetrahedron> tetrahedra_;
  Eigen::VectorXd rest_positions_;
  std::vector<TetrahedronRest> rest_;
  double lambda_ = 0.0, mu_ = 0.0;  ///< Lame parameters, Pa
  /// Per element, (Ke x0)_i: the rest-frame force offset that a rotation turns into f0'.
  std::vector<std::array<Eigen::Vector3d, 4>> rest_forces_;
  std::vector<std::array<int, 16>> block_index_;  ///< per element, slot of block (i, j) at 4i + j
  /// Node i's elements and its corner in each, as 4 e + corner, at incidence_start_[i] ..
  /// incidence_start_[i + 1] in element order.
  std::vector<int> incidences_, incidence_start_;
  /// An element under its current rotation: sqrt(V) R grad N_i (R Ke_ij R^T is their isotropic
  /// block) and R (Ke x0)_i.
  struct WarpedElement {
    std::array<Eigen::Vector3d, 4> gradients, offsets;
  };
  WarpedElement warp(int e) const;
  void warpAvx2(int e);  ///< warped_[e] = warp(e) with 4-wide vectors (other bits: FMA)
  /// Per element, for the row-by-row assembly.
  std::vector<WarpedElement> warped_;
  std::vector<Eigen::Matrix3d> rotations_;
  /// Tetrahedra: the energy V psi(R^T F - I); cells: 1/2 u^T Ke u with u_i = R^T x_i - x0_i.
  double tetrahedronEnergy(int e, const Eigen::Matrix3d& r, const Eigen::Matrix3d& f) const;
  double cellEnergy(const CellElement& cell, const Eigen::Matrix3d& r,
                    const Eigen::VectorXd& x) const;
  /// Element e (tetrahedra first, then cells): F at x (a cell's at its centre), and its energy
  /// with rotation r (a tetrahedron's from F, a cell's from x).
  Eigen::Matrix3d elementDeformationGradient(int e, const Eigen::VectorXd& x) const;
  double elementEnergy(int e, const Eigen::Matrix3d& r, const Eigen::Matrix3d& f,
                       const Eigen::VectorXd& x) const;
  /// Per element, the sums of the rotation update.
  struct ElementSums {
    int inverted = 0;
    double largest_change2 = 0.0;  ///< |R_new - R_old|^2 (Frobenius) = 8 sin^2(angle / 2)
    double energy = 0.0, energy_before = 0.0;
    ElementSums& operator+=(const ElementSums& other);
  };
  mutable std::vector<ElementSums> partial_sums_;
  mutable std::vector<double> partial_energies_;
  int threads_ = 1;
  BlockSparseMatrix stiffness_;
  Eigen::VectorXd force_offset_;
};

}  // namespace deformable_sim::core
