// The Neo-Hookean law (neo_hookean.h) as a body steps through it (elements/elastic_model.h): at x
// its forces and energy, and one of two matrices in the warped stiffness's block pattern.
// - The warped stiffness of the same elements (corotational_elasticity.h), rotated by the
//   elements' rotations where it is assembled: the law's tangent at rest and, for moderate
//   strains, close to it (it leaves out the stress's own stiffness and the law's change of
//   stiffness with strain). Iterations with it converge linearly, by a strain's worth at a time,
//   and cost no eigen-decomposition.
// - The exact tangent, each element's block projected onto its non-negative eigenvalues so that
//   the step's matrix stays positive definite: Newton's convergence at any strain (but for the
//   projection), at several times the cost.
// Either matrix may be kept while later linearizations move only the offset f0 (assembleOffset).
// The linearization's energy, E(x0) - f(x0).(x - x0) + 1/2 (x - x0)^T K (x - x0), is what the
// body's step weighs against the law's own; the law's forces decide when the iterations have
// converged, so both matrices reach the same answer.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "deformable_sim/core/elements/corotational_elasticity.h"
#include "deformable_sim/core/elements/elastic_model.h"
#include "deformable_sim/core/elements/mesh.h"
#include "deformable_sim/core/materials/hyperelastic_elements.h"

namespace deformable_sim::core {

class NeoHookeanElasticity : public ElasticModel {
 public:
  /// Validates the material (std::invalid_argument) and the mesh's elements; builds the pattern.
  NeoHookeanElasticity(const Mesh& mesh, const LinearElasticMaterial& material);

  void setMaterial(const LinearElasticMaterial& material) override;
  void setThreads(int threads) override;
  bool followsPositions() const override { return true; }
  /// The exact tangent (true) or the warped stiffness (false, the default).
  void useExactTangent(bool exact) override { exact_tangent_ = exact; }
  bool usesExactTangent() const override { return exact_tangent_; }
  Update linearizeAt(const Eigen::VectorXd& x) override;
  /// The law's forces at x less -(K x + f0) of the linearization before (infinite before any).
  const Eigen::VectorXd& forceMismatch() const override { return mismatch_; }
  /// K (the warped stiffness with the elements' rotations at x0, or the exact tangent), and f0.
  void assemble() override;
  void assembleOffset() override;
  const BlockSparseMatrix& stiffness() const override { return stiffness_; }
  const Eigen::VectorXd& forceOffset() const override { return force_offset_; }
  double elasticEnergy(const Eigen::VectorXd& x) const override;
  double lawEnergy(const Eigen::VectorXd& x) const override { return elements_.energy(x); }
  /// The elements' polar rotations (a cell's at its centre) of the last warped assembly.
  const std::vector<Eigen::Matrix3d>& rotations() const override { return warped_.rotations(); }
  /// A cell's at its first integration point.
  Eigen::Matrix3d deformationGradient(int e, const Eigen::VectorXd& x) const override {
    return elements_.elementDeformationGradient(e, x);
  }

  const HyperelasticElements& elements() const { return elements_; }

 private:
  /// stiffness_ = the exact tangent at linearized_at_, each element's block projected.
  void assembleExactTangent();
  /// f0 and the energy's constant for stiffness_ at linearized_at_.
  void setOffset();

  HyperelasticElements elements_;
  CorotationalElasticity warped_;  ///< the other matrix, and the elements' rotations
  bool exact_tangent_ = false;
  BlockSparseMatrix stiffness_;  ///< K: one object whichever matrix, as the body points at it
  /// Per element, the slot in stiffness_ of its block (i, j) at kMaxNodes i + j.
  std::vector<std::array<int, HyperelasticElements::kMaxNodes * HyperelasticElements::kMaxNodes>>
      block_index_;
  Eigen::VectorXd force_offset_;
  Eigen::VectorXd linearized_at_;  ///< x0 of the last linearizeAt()
  double energy_at_ = 0.0;         ///< E(x0)
  /// K, f0 and the energy's constant hold a linearization of the current material (the last
  /// assembled, until the next assembly: later linearizeAt() calls are weighed against it).
  bool has_matrix_ = false;
  double energy_constant_ = 0.0;           ///< c in 1/2 x^T K x + f0.x + c
  mutable Eigen::VectorXd product_;        ///< K x, for elasticEnergy()
  mutable bool product_is_of_x0_ = false;  ///< product_ = K linearized_at_ with the K there is
  Eigen::VectorXd forces_;                 ///< the law's forces at the last linearizeAt()
  Eigen::VectorXd mismatch_;               ///< forceMismatch()
};

}  // namespace deformable_sim::core
