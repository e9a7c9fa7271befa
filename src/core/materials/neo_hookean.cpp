#include "deformable_sim/core/materials/neo_hookean.h"

#include <Eigen/Geometry>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace deformable_sim::core {

namespace {

/// The change of cof F along dF: each column is a cross product of two of F's columns.
Eigen::Matrix3d cofactorChange(const Eigen::Matrix3d& f, const Eigen::Matrix3d& df) {
  Eigen::Matrix3d dc;
  for (int k = 0; k < 3; ++k) {
    const int a = (k + 1) % 3, b = (k + 2) % 3;
    dc.col(k) = df.col(a).cross(f.col(b)) + f.col(a).cross(df.col(b));
  }
  return dc;
}

}  // namespace

Eigen::Matrix3d cofactor(const Eigen::Matrix3d& f) {
  Eigen::Matrix3d c;
  for (int k = 0; k < 3; ++k) c.col(k) = f.col((k + 1) % 3).cross(f.col((k + 2) % 3));
  return c;
}

NeoHookean NeoHookean::fromYoungPoisson(double youngs_modulus, double poisson_ratio) {
  if (!(youngs_modulus > 0.0) || !(poisson_ratio > -1.0 && poisson_ratio < 0.5)) {
    std::ostringstream message;
    message << "Neo-Hookean material needs E > 0 and -1 < nu < 0.5, got E = " << youngs_modulus
            << " Pa, nu = " << poisson_ratio;
    throw std::invalid_argument(message.str());
  }
  const double mu = youngs_modulus / (2.0 * (1.0 + poisson_ratio));
  const double bulk = youngs_modulus / (3.0 * (1.0 - 2.0 * poisson_ratio));
  return NeoHookean(mu / 2.0, 2.0 / bulk);
}

NeoHookean::NeoHookean(double c10, double d1) : c10_(c10), d1_(d1) {
  if (!(c10 > 0.0) || !(d1 > 0.0) || !std::isfinite(c10) || !std::isfinite(d1)) {
    std::ostringstream message;
    message << "Neo-Hookean material needs C10 > 0 and D1 > 0, got C10 = " << c10
            << " Pa, D1 = " << d1 << " 1/Pa";
    throw std::invalid_argument(message.str());
  }
}

NeoHookean::VolumeFactor NeoHookean::volumeFactor(double j) {
  const double at = std::max(j, kSmallestVolumeRatio);
  const double root = std::cbrt(at);  // cheaper than pow, and as exact
  const double value = 1.0 / (root * root);
  const double slope = -2.0 / 3.0 * value / at;
  const double curvature = 10.0 / 9.0 * value / (at * at);
  if (j >= kSmallestVolumeRatio) return {value, slope, curvature};
  const double below = j - kSmallestVolumeRatio;  // < 0
  return {value + slope * below + 0.5 * curvature * below * below, slope + curvature * below,
          curvature};
}

double NeoHookean::energyDensity(const Eigen::Matrix3d& f) const {
  const double j = f.determinant();
  return c10_ * (volumeFactor(j).value * f.squaredNorm() - 3.0) + (j - 1.0) * (j - 1.0) / d1_;
}

Eigen::Matrix3d NeoHookean::firstPiola(const Eigen::Matrix3d& f) const {
  return energyAndStress(f).piola;
}

NeoHookean::EnergyAndStress NeoHookean::energyAndStress(const Eigen::Matrix3d& f) const {
  // dI1/dF = 2 F and dJ/dF = cof F; J = F's first column dotted with cof F's.
  const Eigen::Matrix3d c = cofactor(f);
  const double j = f.col(0).dot(c.col(0)), i1 = f.squaredNorm();
  const VolumeFactor g = volumeFactor(j);
  return {c10_ * (g.value * i1 - 3.0) + (j - 1.0) * (j - 1.0) / d1_,
          c10_ * (2.0 * g.value * f + g.slope * i1 * c) + 2.0 * (j - 1.0) / d1_ * c};
}

Eigen::Matrix<double, 9, 9> NeoHookean::firstPiolaDerivative(const Eigen::Matrix3d& f) const {
  const double j = f.determinant(), i1 = f.squaredNorm();
  const VolumeFactor g = volumeFactor(j);
  const Eigen::Matrix3d c = cofactor(f);
  const double h_slope = 2.0 * (j - 1.0) / d1_, h_curvature = 2.0 / d1_;
  Eigen::Matrix<double, 9, 9> derivative;
  // dP along each unit direction dF = e_s e_d^T is column 3 d + s.
  for (int d = 0; d < 3; ++d) {
    for (int s = 0; s < 3; ++s) {
      Eigen::Matrix3d df = Eigen::Matrix3d::Zero();
      df(s, d) = 1.0;
      const double dj = c(s, d), di1 = 2.0 * f(s, d);
      const Eigen::Matrix3d dc = cofactorChange(f, df);
      const Eigen::Matrix3d dp =
          c10_ * (2.0 * g.slope * dj * f + 2.0 * g.value * df + g.curvature * dj * i1 * c +
                  g.slope * di1 * c + g.slope * i1 * dc) +
          h_curvature * dj * c + h_slope * dc;
      derivative.col(3 * d + s) = dp.reshaped();
    }
  }
  return derivative;
}

}  // namespace deformable_sim::core
