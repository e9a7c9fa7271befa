// The linear tetrahedron: what depends only on the rest shape (computed once per element) and the
// per-step kinematics. Shape-function gradients follow the edge-matrix construction of OpenTissue's
// compute_B; the stiffness is Ke = V B^T D B.
#pragma once

#include <Eigen/Core>
#include <array>

#include "deformable_sim/core/material.h"

namespace deformable_sim::core {

/// A 12x12 element matrix stored as 4x4 blocks of 3x3: blocks[i][j] couples node i with node j.
using ElementBlocks = std::array<std::array<Eigen::Matrix3d, 4>, 4>;

/// Rest-shape data of one linear tetrahedron.
struct TetrahedronRest {
  double volume = 0.0;                       ///< V, m^3 (positive for a valid element)
  Eigen::Matrix3d rest_edges_inverse;        ///< Dm^-1, Dm = [X1-X0, X2-X0, X3-X0], 1/m
  std::array<Eigen::Vector3d, 4> gradients;  ///< grad N_i, constant over the element, 1/m
  ElementBlocks stiffness;                   ///< Ke = V B^T D B, N/m
};

/// Rest data of the tetrahedron with rest corners x[0..3]. The caller guarantees positive volume
/// (the mesh readers reorder or reject other elements).
TetrahedronRest computeTetrahedronRest(const std::array<Eigen::Vector3d, 4>& x,
                                       const LinearElasticMaterial& material);

/// Deformation gradient F = Ds Dm^-1 with Ds = [x1-x0, x2-x0, x3-x0] (current positions).
inline Eigen::Matrix3d deformationGradient(const TetrahedronRest& rest, const Eigen::Vector3d& x0,
                                           const Eigen::Vector3d& x1, const Eigen::Vector3d& x2,
                                           const Eigen::Vector3d& x3) {
  Eigen::Matrix3d ds;
  ds.col(0) = x1 - x0;
  ds.col(1) = x2 - x0;
  ds.col(2) = x3 - x0;
  return ds * rest.rest_edges_inverse;
}

}  // namespace deformable_sim::core
