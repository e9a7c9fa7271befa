#include "deformable_sim/core/elements/incompatible_modes.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <stdexcept>

#include "deformable_sim/core/elements/tetrahedron.h"

namespace deformable_sim::core {

namespace {

constexpr int kNodes = 8;
constexpr int kModes = 3;  // one shape 1 - xi_k^2 per natural direction, in x, y and z each

Eigen::Matrix3d naturalJacobian(const CellVectors& corners, const ShapeValues& shape) {
  Eigen::Matrix3d j = Eigen::Matrix3d::Zero();
  for (int k = 0; k < kNodes; ++k) j.noalias() += corners[k] * shape.gradients[k].transpose();
  return j;
}

}  // namespace

bool incompatibleModesApply(const OctantFractions& fractions) {
  for (double f : fractions) {
    if (!(f >= kModesMinOctantFraction)) return false;
  }
  return true;
}

Eigen::MatrixXd incompatibleModesStiffness(const CellVectors& corners, double lambda, double mu,
                                           const OctantFractions* fractions) {
  constexpr CellType kHex = CellType::kHexahedron;
  const Eigen::Matrix3d j0 = naturalJacobian(corners, shapeFunctions(kHex, naturalCentre(kHex)));
  const double det0 = j0.determinant();
  if (!(det0 > 0.0)) throw std::invalid_argument("incompatible modes: inverted hexahedron");
  const Eigen::Matrix3d j0_inverse_transpose = j0.inverse().transpose();
  // The nodes' and the modes' gradients act alike: K over "points" 0..7 (nodes) and 8..10
  // (modes), then the modes condensed out.
  constexpr int n = kNodes + kModes;
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  for (const QuadraturePoint& q : materialQuadrature(kHex, fractions)) {
    const ShapeValues shape = shapeFunctions(kHex, q.xi);
    const Eigen::Matrix3d j = naturalJacobian(corners, shape);
    const double det = j.determinant();
    if (!(det > 0.0)) throw std::invalid_argument("incompatible modes: inverted hexahedron");
    std::array<Eigen::Vector3d, n> g;
    const Eigen::Matrix3d inverse_transpose = j.inverse().transpose();
    for (int a = 0; a < kNodes; ++a) g[a] = inverse_transpose * shape.gradients[a];
    // d(1 - xi_m^2)/dxi = -2 xi_m e_m, taken through J0 and scaled by det J0 / det J (Taylor).
    for (int m = 0; m < kModes; ++m) {
      g[kNodes + m] =
          (det0 / det) * j0_inverse_transpose * (-2.0 * q.xi[m] * Eigen::Vector3d::Unit(m));
    }
    const double volume = q.weight * det;
    for (int a = 0; a < n; ++a) {
      for (int b = 0; b < n; ++b) {
        k.block<3, 3>(3 * a, 3 * b) += stiffnessBlock(lambda * volume, mu * volume, g[a], g[b]);
      }
    }
  }
  constexpr int u = 3 * kNodes, alpha = 3 * kModes;
  const Eigen::MatrixXd kaa = k.bottomRightCorner(alpha, alpha);
  const Eigen::MatrixXd kau = k.bottomLeftCorner(alpha, u);
  // Kaa is singular when material fills only some octants (the modes some points cannot see):
  // its pseudo-inverse leaves those modes out.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(kaa);
  const Eigen::VectorXd values = eigen.eigenvalues();
  const double cutoff = 1e-10 * values.cwiseAbs().maxCoeff();
  const Eigen::VectorXd inverse_values =
      values.unaryExpr([cutoff](double v) { return v > cutoff ? 1.0 / v : 0.0; });
  const Eigen::MatrixXd projected = eigen.eigenvectors().transpose() * kau;
  const Eigen::MatrixXd condensed =
      k.topLeftCorner(u, u) - projected.transpose() * inverse_values.asDiagonal() * projected;
  return 0.5 * (condensed + condensed.transpose());
}

}  // namespace deformable_sim::core
