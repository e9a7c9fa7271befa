// The hexahedron with incompatible modes (Wilson et al. 1973; Taylor, Beresford and Wilson 1976,
// "A non-conforming element for stress analysis"): nine internal displacement modes
// (1 - xi_k^2 in each direction) let a full-integration hexahedron bend without shear locking,
// then are condensed out of its stiffness once, at rest. CalculiX calls it C3D8I. A voxel grid,
// a few cells through a part, needs it: the fully integrated hexahedron is far too stiff there.
#pragma once

#include <Eigen/Core>

#include "deformable_sim/core/cell.h"
#include "deformable_sim/core/mesh.h"

namespace deformable_sim::core {

/// Below this material fraction in any octant a hexahedron keeps plain full integration: with
/// little material at some integration points the nine modes can cancel the strain at the
/// others, and the cell goes soft (a cell filled in one octant would have no stiffness at all).
constexpr double kModesMinOctantFraction = 0.25;

/// Whether a hexahedron with these material fractions takes the incompatible modes.
bool incompatibleModesApply(const OctantFractions& fractions);

/// The condensed rest stiffness (24 x 24, node-major) of a hexahedron with rest corners
/// `corners` (Gmsh order), Lame parameters lambda and mu (Pa), and the material `fractions`
/// (null: full) weighting its 2 x 2 x 2 integration points as in cellStiffness. The modes'
/// gradients use the Jacobian at the centre (Taylor's correction), so the element passes the
/// patch test when distorted. Throws std::invalid_argument for an inverted cell.
Eigen::MatrixXd incompatibleModesStiffness(const CellVectors& corners, double lambda, double mu,
                                           const OctantFractions* fractions = nullptr);

}  // namespace deformable_sim::core
