// The Neo-Hookean law (neo_hookean.h) as a body steps through it (elements/elastic_model.h):
// linearized at x by its tangent, each element's block projected onto its non-negative
// eigenvalues so that the step's matrix stays positive definite, in the same block pattern as
// the warped stiffness. The linearization's energy, E(x0) - f(x0).(x - x0) + 1/2 (x - x0)^T K
// (x - x0), is what the body's step weighs against the law's own at the step's end.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "deformable_sim/core/elements/elastic_model.h"
#include "deformable_sim/core/elements/mesh.h"
#include "deformable_sim/core/materials/hyperelastic_elements.h"

namespace deformable_sim::core {

class NeoHookeanElasticity : public ElasticModel {
 public:
  /// Validates the material (std::invalid_argument) and the mesh's elements; builds the pattern.
  NeoHookeanElasticity(const Mesh& mesh, const LinearElasticMaterial& material);

  void setMaterial(const LinearElasticMaterial& material) override;
  void setThreads(int threads) override { threads_ = threads; }
  bool followsPositions() const override { return true; }
  Update linearizeAt(const Eigen::VectorXd& x) override;
  void assemble() override;
  const BlockSparseMatrix& stiffness() const override { return stiffness_; }
  const Eigen::VectorXd& forceOffset() const override { return force_offset_; }
  double elasticEnergy(const Eigen::VectorXd& x) const override;
  double lawEnergy(const Eigen::VectorXd& x) const override { return elements_.energy(x); }
  const std::vector<Eigen::Matrix3d>& rotations() const override { return rotations_; }
  /// A cell's at its first integration point.
  Eigen::Matrix3d deformationGradient(int e, const Eigen::VectorXd& x) const override {
    return elements_.elementDeformationGradient(e, x);
  }

  const HyperelasticElements& elements() const { return elements_; }

 private:
  HyperelasticElements elements_;
  int threads_ = 1;
  BlockSparseMatrix stiffness_;
  /// Per element, the slot in stiffness_ of its block (i, j) at kMaxNodes i + j.
  std::vector<std::array<int, HyperelasticElements::kMaxNodes * HyperelasticElements::kMaxNodes>>
      block_index_;
  Eigen::VectorXd force_offset_;
  std::vector<Eigen::Matrix3d> rotations_;
  Eigen::VectorXd linearized_at_;    ///< x0 of the last linearizeAt()
  double energy_at_ = 0.0;           ///< E(x0)
  bool assembled_ = false;           ///< K, f0 and the energy's constant are of linearized_at_
  double energy_constant_ = 0.0;     ///< c in 1/2 x^T K x + f0.x + c
  mutable Eigen::VectorXd product_;  ///< K x, for elasticEnergy()
  Eigen::VectorXd forces_;           ///< the law's forces at the last linearizeAt()
};

}  // namespace deformable_sim::core
