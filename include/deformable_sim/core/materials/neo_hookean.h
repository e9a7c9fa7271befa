// Compressible Neo-Hookean elasticity in CalculiX's (and Abaqus's) form: the strain energy per
// unit rest volume
//   W(F) = C10 (J^(-2/3) I1 - 3) + (J - 1)^2 / D1,    I1 = tr(F^T F), J = det F,
// with C10 = mu / 2 and D1 = 2 / K from Young's modulus and Poisson's ratio, so that small strains
// give the linear law with the same E and nu (Drake's Neo-Hookean, with plain Lame constants in
// another energy, does not).
//
// Written with the cofactor cof F = J F^-T, a polynomial in F, in place of F^-T: then the stress
// and its derivative are finite wherever the J-terms are. Below kSmallestVolumeRatio the factor
// J^(-2/3) is continued by its second-order Taylor polynomial, which stays positive and finite
// through J = 0 and beyond: an element crushed flat or turned inside out has a finite energy that
// grows as it is inverted further, and finite forces that push it back out.
#pragma once

#include <Eigen/Core>

namespace deformable_sim::core {

class NeoHookean {
 public:
  /// J below which J^(-2/3) takes its Taylor continuation; far below any compression a
  /// reference asks for (0.1 is a 90 % loss of volume).
  static constexpr double kSmallestVolumeRatio = 0.1;

  /// C10 = mu / 2 and D1 = 2 / K for Young's modulus E > 0 (Pa) and Poisson's ratio nu in
  /// (-1, 0.5). Throws std::invalid_argument otherwise.
  static NeoHookean fromYoungPoisson(double youngs_modulus, double poisson_ratio);
  /// Throws std::invalid_argument unless C10 > 0 (Pa) and D1 > 0 (1/Pa).
  NeoHookean(double c10, double d1);

  double c10() const { return c10_; }
  double d1() const { return d1_; }

  /// W(F), J/m^3.
  double energyDensity(const Eigen::Matrix3d& f) const;
  /// The first Piola-Kirchhoff stress P = dW/dF, Pa.
  Eigen::Matrix3d firstPiola(const Eigen::Matrix3d& f) const;
  /// W(F) and P(F) together, sharing J and cof F: what a force evaluation needs.
  struct EnergyAndStress {
    double energy;          ///< J/m^3
    Eigen::Matrix3d piola;  ///< Pa
  };
  EnergyAndStress energyAndStress(const Eigen::Matrix3d& f) const;
  /// dP/dF as a 9x9 matrix on column-major vec(F): entry (3 c + r, 3 d + s) = dP_rc / dF_sd.
  Eigen::Matrix<double, 9, 9> firstPiolaDerivative(const Eigen::Matrix3d& f) const;

 private:
  /// g(J) = J^(-2/3) (continued below kSmallestVolumeRatio) and its first two derivatives.
  struct VolumeFactor {
    double value, slope, curvature;
  };
  static VolumeFactor volumeFactor(double j);

  double c10_;
  double d1_;
};

/// The cofactor matrix of F, J F^-T where F is invertible; defined for every F.
Eigen::Matrix3d cofactor(const Eigen::Matrix3d& f);

}  // namespace deformable_sim::core
