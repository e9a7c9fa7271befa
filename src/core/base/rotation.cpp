#include "deformable_sim/core/base/rotation.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>

#include "deformable_sim/core/base/cpu_features.h"

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

namespace {

// A documented numeric kernel, kept in one piece: the iteration runs over arrays of matrix
// entries that the compiler vectorizes as one loop nest, and it is inlined into each caller below
// so that it is compiled for the caller's instruction set (a helper would have to be inlined the
// same way to keep that).
__attribute__((always_inline)) inline void extractRotationsInLockstep(
    const Eigen::Matrix3d* deformation_gradients, Eigen::Matrix3d* rotations, int count) {
  // The Newton-Schulz iteration of extractRotation for kRotationBatch matrices in lockstep, entry
  // by entry across them (x[k][l]: entry k, column-major, of matrix l), a form the compiler
  // vectorizes. Every matrix takes updates until all have converged; the extra ones keep a
  // converged iterate at R to rounding. Matrices the iteration does not suit (det F small or
  // negative, far from a rotation, not converged in time) take extractRotation alone.
  constexpr int kLanes = kRotationBatch;
  double x[9][kLanes];
  bool alone[kLanes];
  for (int l = 0; l < kLanes; ++l) {
    const Eigen::Matrix3d& f =
        l < count ? deformation_gradients[l] : Eigen::Matrix3d::Identity().eval();
    for (int k = 0; k < 9; ++k) x[k][l] = f.data()[k];
    alone[l] = l < count && !(f.determinant() > kNewtonMinDeterminant);
  }
  bool converged = false;
  for (int iteration = 0; iteration < kSchulzMaxIterations && !converged; ++iteration) {
    // G = X^T X - I (symmetric): g[3 a + b] = column a . column b - delta_ab.
    double g[9][kLanes], deviation2[kLanes];
    for (int a = 0; a < 3; ++a) {
      for (int b = a; b < 3; ++b) {
        for (int l = 0; l < kLanes; ++l) {
          g[3 * a + b][l] = x[3 * a][l] * x[3 * b][l] + x[3 * a + 1][l] * x[3 * b + 1][l] +
                            x[3 * a + 2][l] * x[3 * b + 2][l] - (a == b ? 1.0 : 0.0);
          g[3 * b + a][l] = g[3 * a + b][l];
        }
      }
    }
    for (int l = 0; l < kLanes; ++l) {
      double sum = 0.0;
      for (int k = 0; k < 9; ++k) sum += g[k][l] * g[k][l];
      deviation2[l] = sum;
    }
    converged = true;
    for (int l = 0; l < kLanes; ++l) {
      if (alone[l]) continue;
      if (!(deviation2[l] < kSchulzMaxDeviation2)) {
        alone[l] = true;  // too far from a rotation (or diverging)
      } else if (!(deviation2[l] < kSchulzLastDeviation2)) {
        converged = false;
      }
    }
    // X <- X - X G / 2, column by column.
    double next[9][kLanes];
    for (int column = 0; column < 3; ++column) {
      for (int row = 0; row < 3; ++row) {
        for (int l = 0; l < kLanes; ++l) {
          next[3 * column + row][l] =
              x[3 * column + row][l] -
              0.5 * (x[row][l] * g[column][l] + x[3 + row][l] * g[3 + column][l] +
                     x[6 + row][l] * g[6 + column][l]);
        }
      }
    }
    for (int k = 0; k < 9; ++k) {
      for (int l = 0; l < kLanes; ++l) x[k][l] = next[k][l];
    }
  }
  for (int l = 0; l < count; ++l) {
    if (alone[l] || !converged) {
      rotations[l] = extractRotation(deformation_gradients[l]);
      continue;
    }
    for (int k = 0; k < 9; ++k) rotations[l].data()[k] = x[k][l];
  }
}

void extractRotationsPortable(const Eigen::Matrix3d* deformation_gradients,
                              Eigen::Matrix3d* rotations, int count) {
  extractRotationsInLockstep(deformation_gradients, rotations, count);
}

#if defined(__x86_64__)
// Four lanes: one 4-wide vector per entry.
__attribute__((target("avx2,fma"))) void extractRotationsAvx2(
    const Eigen::Matrix3d* deformation_gradients, Eigen::Matrix3d* rotations, int count) {
  extractRotationsInLockstep(deformation_gradients, rotations, count);
}
#endif

}  // namespace

void extractRotations(const Eigen::Matrix3d* deformation_gradients, Eigen::Matrix3d* rotations,
                      int count) {
#if defined(__x86_64__)
  if (hasAvx2Fma()) {
    extractRotationsAvx2(deformation_gradients, rotations, count);
    return;
  }
#endif
  extractRotationsPortable(deformation_gradients, rotations, count);
}

}  // namespace deformable_sim::core
