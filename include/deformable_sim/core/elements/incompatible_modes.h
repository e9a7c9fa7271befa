// The hexahedron with incompatible modes (Wilson et al. 1973; Taylor, Beresford and Wilson 1976,
// "A non-conforming element for stress analysis"): nine internal displacement modes
// (1 - xi_k^2 in each direction) let a full-integration hexahedron bend without shear locking,
// then are condensed out of its stiffness once, at rest. CalculiX calls it C3D8I. A voxel grid,
// a few cells through a part, needs it: the fully integrated hexahedron is far too stiff there.
#pragma once

#include <Eigen/Core>

#include "deformable_sim/core/elements/cell.h"
#include "deformable_sim/core/elements/mesh.h"

namespace deformable_sim::core {

/// Below this material fraction in any octant a hexahedron keeps plain full integration: where
/// little material holds them, the nine modes' own stiffness is nearly singular, and condensing
/// them leaves the cell with nearly free motions that slow the solver by orders of magnitude
/// (doc/physics.md, "Cells a surface cuts").
constexpr double kModesMinOctantFraction = 0.25;

/// Whether a hexahedron with these material fractions takes the incompatible modes.
bool incompatibleModesApply(const OctantFractions& fractions);

/// The condensed rest stiffness (24 x 24, node-major) of a hexahedron with rest corners
/// `corners` (Gmsh order), Lame parameters lambda and mu (Pa), and the material `fractions`
/// (null: full) integrated as in cellStiffness (materialQuadrature). The modes'
/// gradients use the Jacobian at the centre (Taylor's correction), so the element passes the
/// patch test when distorted. Throws std::invalid_argument for an inverted cell.
Eigen::MatrixXd incompatibleModesStiffness(const CellVectors& corners, double lambda, double mu,
                                           const OctantFractions* fractions = nullptr);

}  // namespace deformable_sim::core
