#include "deformable_sim/core/rotation.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>

namespace deformable_sim::core {

namespace {

// Below this det F the Newton iteration would start far from R (and at det F <= 0 it would
// converge to the wrong factor): the SVD takes over.
constexpr double kNewtonMinDeterminant = 0.05;
constexpr int kNewtonMaxIterations = 20;
// Quadratic convergence: the error after an update d is about d^2 / 2, so an update of 3e-7
// leaves an iterate within 5e-14 of R.
constexpr double kNewtonConvergedUpdate2 = 1e-13;
// Scaling only pays while the singular values are far from one.
constexpr double kNewtonScaledUpdate2 = 1e-4;
// Near a rotation, |X^T X - I|^2 below this (strains up to about a fifth), the Newton-Schulz
// iteration takes over: X = R (I + E) goes to R (I - 3/2 E^2 + ...), so the strain's square
// shrinks quadratically with products alone (no division or root on the chain from one iterate
// to the next). Once |X^T X - I|^2 < 1e-14 (|E| < 5e-8), one more step leaves an error of
// about 4e-15.
constexpr double kSchulzMaxDeviation2 = 0.25;
constexpr double kSchulzLastDeviation2 = 1e-14;
constexpr int kSchulzMaxIterations = 8;

// Cofactor matrix C with X^T C = det(X) I, i.e. X^-T = C / det(X) and det(X) = x_0 . c_0.
Eigen::Matrix3d cofactor(const Eigen::Matrix3d& x) {
  Eigen::Matrix3d c;
  c.col(0) = x.col(1).cross(x.col(2));
  c.col(1) = x.col(2).cross(x.col(0));
  c.col(2) = x.col(0).cross(x.col(1));
  return c;
}

}  // namespace

Eigen::Matrix3d extractRotationBySvd(const Eigen::Matrix3d& deformation_gradient) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(deformation_gradient,
                                              Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d u = svd.matrixU();
  const Eigen::Matrix3d& v = svd.matrixV();
  // JacobiSVD sorts singular values in decreasing order: column 2 is the smallest.
  if ((u * v.transpose()).determinant() < 0.0) u.col(2) = -u.col(2);
  return u * v.transpose();
}

Eigen::Matrix3d extractRotation(const Eigen::Matrix3d& deformation_gradient) {
  Eigen::Matrix3d x = deformation_gradient;
  Eigen::Matrix3d c = cofactor(x);
  double det = x.col(0).dot(c.col(0));
  if (!(det > kNewtonMinDeterminant)) return extractRotationBySvd(deformation_gradient);
  for (int k = 0; k < kSchulzMaxIterations; ++k) {
    const Eigen::Matrix3d deviation = x.transpose() * x - Eigen::Matrix3d::Identity();
    const double deviation2 = deviation.squaredNorm();
    if (!(deviation2 < kSchulzMaxDeviation2)) break;  // too far from a rotation: Newton
    x -= 0.5 * x * deviation;                         // X (3 I - X^T X) / 2
    if (deviation2 < kSchulzLastDeviation2) return x;
  }
  x = deformation_gradient;  // not converged within the cap: Newton from F
  bool scaled = true;
  for (int k = 0; k < kNewtonMaxIterations; ++k) {
    // X+ = (g X + X^-T / g) / 2 with X^-T = C / det.
    const double inverse_det = 1.0 / det;
    double g = 1.0;
    if (scaled) {
      // Frobenius-norm scaling (Higham 1986), g^2 = |X^-T| / |X|, evens out the singular values
      // in the first steps.
      g = std::sqrt(std::sqrt(c.squaredNorm() / x.squaredNorm()) * inverse_det);
    }
    const Eigen::Matrix3d next = (0.5 * g) * x + (0.5 * inverse_det / g) * c;
    const double update2 = (next - x).squaredNorm();
    x = next;
    if (update2 < kNewtonConvergedUpdate2) return x;
    scaled = update2 > kNewtonScaledUpdate2;
    c = cofactor(x);
    det = x.col(0).dot(c.col(0));
  }
  return extractRotationBySvd(deformation_gradient);  // not reached for det F > the threshold
}

}  // namespace deformable_sim::core
