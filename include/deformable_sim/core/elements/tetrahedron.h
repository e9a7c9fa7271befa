// The linear tetrahedron: what depends only on the rest shape (computed once per element) and the
// per-step kinematics. Shape-function gradients follow the edge-matrix construction of OpenTissue's
// compute_B. For an isotropic material the stiffness Ke = V B^T D B has the closed form
//   Ke_ij = V (lambda g_i g_j^T + mu g_j g_i^T + mu (g_i . g_j) I),
// so it is never stored: a step builds each block from the four gradients, and the warped block
// R Ke_ij R^T is the same formula with the rotated gradients R g_i (rotations keep g_i . g_j).
#pragma once

#include <Eigen/Core>
#include <array>

#include "deformable_sim/core/elements/material.h"

namespace deformable_sim::core {

/// A 12x12 element matrix stored as 4x4 blocks of 3x3: blocks[i][j] couples node i with node j.
using ElementBlocks = std::array<std::array<Eigen::Matrix3d, 4>, 4>;

/// Rest-shape data of one linear tetrahedron.
struct TetrahedronRest {
  double volume = 0.0;                       ///< V, m^3 (positive for a valid element)
  std::array<Eigen::Vector3d, 4> gradients;  ///< grad N_i, constant over the element, 1/m
};

/// Rest data of the tetrahedron with rest corners x[0..3]. The caller guarantees positive volume
/// (the mesh readers reorder or reject other elements).
TetrahedronRest computeTetrahedronRest(const std::array<Eigen::Vector3d, 4>& x);

/// Block (i, j) of Ke from the gradients g_i, g_j (rotated or not) and lambda V, mu V. Written
/// entry by entry so that block (j, i) is the exact transpose of block (i, j), bit for bit: an
/// assembly may compute a pair once or twice and get the same sums.
inline Eigen::Matrix3d stiffnessBlock(double lambda_volume, double mu_volume,
                                      const Eigen::Vector3d& gi, const Eigen::Vector3d& gj) {
  Eigen::Matrix3d k;
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r)
      k(r, c) = lambda_volume * (gi[r] * gj[c]) + mu_volume * (gj[r] * gi[c]);
  }
  k.diagonal().array() += mu_volume * gi.dot(gj);
  return k;
}

/// The element's rest stiffness Ke, N/m (for tests, energies and diagnostics; a step builds the
/// blocks it needs on the fly).
ElementBlocks elementStiffness(const TetrahedronRest& rest, const LinearElasticMaterial& material);

/// Deformation gradient F = sum_i x_i grad N_i^T (= Ds Dm^-1) at current corner positions.
inline Eigen::Matrix3d deformationGradient(const TetrahedronRest& rest, const Eigen::Vector3d& x0,
                                           const Eigen::Vector3d& x1, const Eigen::Vector3d& x2,
                                           const Eigen::Vector3d& x3) {
  return x0 * rest.gradients[0].transpose() + x1 * rest.gradients[1].transpose() +
         x2 * rest.gradients[2].transpose() + x3 * rest.gradients[3].transpose();
}

}  // namespace deformable_sim::core
