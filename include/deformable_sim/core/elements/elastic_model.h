// What a finite-element body steps through, whatever its material law: at positions x the law is
// linearized, forces f(x) - K (x' - x) near x, and handed over as a stiffness K in the mesh's
// block pattern and an offset f0 with K x + f0 = -f(x), so that the elastic force of the
// linearization at any x' is -(K x' + f0). The warped stiffness (corotational_elasticity.h) is
// one such law, linearized by its elements' rotations; Neo-Hookean
// (materials/neo_hookean_elasticity.h) another, by its tangent or the warped stiffness. The
// body's implicit step solves with the linearization at the step's start, re-linearizes at the
// end and solves again: for the warped stiffness while the change of rotations gains more energy
// than the step dissipates; for a law that follows the positions by (quasi-)Newton iterations
// with a line search, from the predicted end, until implicit Euler's residual with the law's
// force is small (core/bodies/finite_element_body.h).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "deformable_sim/core/elements/material.h"
#include "deformable_sim/core/solvers/block_sparse_matrix.h"

namespace deformable_sim::core {

class ElasticModel {
 public:
  virtual ~ElasticModel() = default;

  /// What linearizeAt() found at x.
  struct Update {
    int inverted = 0;             ///< elements with det F <= 0
    double largest_change = 0.0;  ///< largest angle by which an element's rotation changed, rad
    double energy = 0.0;          ///< elastic energy of the law at x, J
    double energy_before = 0.0;   ///< elastic energy at x of the linearization before, J
    /// For a law that follows the positions: its largest nodal force at x, N, and the sizes
    /// below which its energy (J) and its difference from the linearization before (N) are
    /// rounding (the terms that cancel in them, times a few machine epsilons). Else zero.
    double largest_force = 0.0;
    double energy_rounding = 0.0;
    double force_rounding = 0.0;
  };

  /// A new material (validated first) for the next assembly; rest shape and pattern stay.
  virtual void setMaterial(const LinearElasticMaterial& material) = 0;
  /// Threads for the element loops; results are the same on any count.
  virtual void setThreads(int threads) = 0;
  /// Whether the law must be linearized again wherever the body moves (else only with the
  /// warping effect: linear elasticity is its own linearization).
  virtual bool followsPositions() const = 0;

  /// Which matrix the next assemble() builds, where the law has a choice: its exact tangent
  /// (Newton's method), or a cheaper one as good at moderate strains (a quasi-Newton method,
  /// slower to converge at large ones). The warped stiffness has one matrix, its own.
  virtual void useExactTangent(bool exact) { (void)exact; }
  virtual bool usesExactTangent() const { return true; }

  /// Linearizes the law at x (rotations, deformation gradients), without assembling yet.
  virtual Update linearizeAt(const Eigen::VectorXd& x) = 0;
  /// For a law that follows the positions: per node, its force at the last linearizeAt()'s x
  /// less the force of the linearization before it there (how far that was off the law), N.
  /// Empty for the warped stiffness, its own linearization.
  virtual const Eigen::VectorXd& forceMismatch() const {
    static const Eigen::VectorXd kNone;
    return kNone;
  }
  /// K and f0 of the last linearizeAt(). Allocates nothing.
  virtual void assemble() = 0;
  /// Only f0 for the last linearizeAt(), K kept as last assembled: the matrix of a step's later
  /// quasi-Newton iterations. By default the whole of assemble().
  virtual void assembleOffset() { assemble(); }
  virtual const BlockSparseMatrix& stiffness() const = 0;  ///< K, N/m
  virtual const Eigen::VectorXd& forceOffset() const = 0;  ///< f0, N
  /// The energy of the last assembled linearization at x, J: the law's own at the positions it
  /// was linearized at. Not for concurrent calls on one object.
  virtual double elasticEnergy(const Eigen::VectorXd& x) const = 0;
  /// The law's own energy at x, J (for a line search; the warped stiffness's with the rotations
  /// of the last linearization).
  virtual double lawEnergy(const Eigen::VectorXd& x) const { return elasticEnergy(x); }
  /// Per element (tetrahedra first, then cells), the rotation of the last linearizeAt(): how far
  /// each has turned (a body keeps answers to impulses while these change little).
  virtual const std::vector<Eigen::Matrix3d>& rotations() const = 0;
  /// Element e's deformation gradient at x (tetrahedra first, then cells; a cell's at a point
  /// of its own: the centre, or its first integration point).
  virtual Eigen::Matrix3d deformationGradient(int e, const Eigen::VectorXd& x) const = 0;
};

}  // namespace deformable_sim::core
