// The pyramid, wedge and hexahedron of seed 004 (Solfec-1.0): isoparametric shape functions in
// natural coordinates xi, their Gauss quadrature, and what a corotational element needs from its
// rest shape. Unlike the tetrahedron's, these gradients vary over the element, so the stiffness
// K = sum_q w_q det J_q B_q^T D B_q is integrated numerically and stored per element.
#pragma once

#include <Eigen/Core>
#include <array>
#include <utility>
#include <vector>

#include "deformable_sim/core/elements/mesh.h"

namespace deformable_sim::core {

constexpr int kMaxCellNodes = 8;
using CellVectors = std::array<Eigen::Vector3d, kMaxCellNodes>;

/// Shape functions N_i and their gradients dN_i/dxi at one natural point (entries past the
/// cell's size are unused).
struct ShapeValues {
  std::array<double, kMaxCellNodes> values{};
  CellVectors gradients;
};

/// Natural coordinates of node i: hexahedron (+-1, +-1, +-1); wedge (0 or 1, 0 or 1, +-1) over
/// the triangle xi1, xi2 >= 0, xi1 + xi2 <= 1; pyramid base (+-1, +-1, 0) and apex (0, 0, 1).
Eigen::Vector3d naturalNode(CellType type, int i);

/// Seed 004's shape functions. The pyramid's are rational, r = xi1 xi2 xi3 / (1 - xi3), on the
/// natural pyramid |xi1|, |xi2| <= 1 - xi3 (its gradients are undefined at the apex itself).
ShapeValues shapeFunctions(CellType type, const Eigen::Vector3d& xi);

/// The centroid of the natural element, where the element's rotation is taken from F.
Eigen::Vector3d naturalCentre(CellType type);

struct QuadraturePoint {
  Eigen::Vector3d xi;
  double weight;  ///< natural volume it stands for; the weights sum to the natural volume
};

/// Hexahedron: 2x2x2 Gauss (full integration, as CalculiX's C3D8). Wedge: the 3-point triangle
/// rule times 2-point Gauss. Pyramid: 2x2x3 Gauss on the cube collapsed onto the pyramid. All
/// integrate the stiffness of an undistorted element exactly.
const std::vector<QuadraturePoint>& quadrature(CellType type);

/// The cell's corner positions, in its node order.
CellVectors cellCorners(const Cell& cell, const std::vector<Eigen::Vector3d>& positions);

/// The integration points of a cell's material, each weight times the material fraction it
/// stands for. A cell filled alike everywhere (null fractions, or every octant the same) takes
/// its own rule. A hexahedron filled unevenly takes 2 x 2 x 2 Gauss points in each octant that
/// holds material, weighted by the octant's fraction: the trilinear field integrated exactly over
/// the material, so that however little of a cell is filled its stiffness has only the six rigid
/// modes as zero-energy modes (one point per octant left a cell filled in one octant a rank of 6,
/// and its nodes free to move without resistance). Other cells: their rule times the mean.
std::vector<QuadraturePoint> materialQuadrature(CellType type, const OctantFractions* fractions);

/// Rest data of one cell.
struct CellRest {
  double volume = 0.0;           ///< m^3
  CellVectors centre_gradients;  ///< grad N_i at the centre, 1/m: F = sum_i x_i g_i^T there
  std::array<double, kMaxCellNodes> shape_integrals{};  ///< integral of N_i dV, m^3
};

/// Throws std::invalid_argument when the isoparametric map is not orientation-preserving
/// (det J <= 0) at an integration point or the centre: an inverted, flat or tangled cell. With
/// `fractions`, the volume and shape integrals are those of the cell's material.
CellRest computeCellRest(CellType type, const CellVectors& corners,
                         const OctantFractions* fractions = nullptr);

/// The smallest and largest det J over the centre and the integration points: both positive for
/// a valid cell, both negative for one listed in mirrored order, mixed for a tangled one.
std::pair<double, double> jacobianRange(CellType type, const CellVectors& corners);

/// The same cell with its node order mirrored (bottom and top swapped; a pyramid's base
/// reversed): turns a mirrored cell into a valid one.
Cell mirrored(const Cell& cell);

/// The rest stiffness (3n x 3n, node-major) for Lame parameters lambda and mu, Pa; of the cell's
/// material with `fractions` (integrated by materialQuadrature).
Eigen::MatrixXd cellStiffness(CellType type, const CellVectors& corners, double lambda, double mu,
                              const OctantFractions* fractions = nullptr);

/// The deformation gradient at the centre from current corner positions.
Eigen::Matrix3d cellDeformationGradient(const CellRest& rest, int size, const CellVectors& x);

}  // namespace deformable_sim::core
