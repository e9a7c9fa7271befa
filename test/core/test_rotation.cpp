#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <array>
#include <cmath>
#include <cstdlib>

#include "deformable_sim/core/base/rotation.h"

namespace dc = deformable_sim::core;

namespace {

void expectProperRotation(const Eigen::Matrix3d& r) {
  ASSERT_TRUE(r.allFinite());
  EXPECT_NEAR((r.transpose() * r - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
}

Eigen::Matrix3d someRotation(double angle, Eigen::Vector3d axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

}  // namespace

TEST(Rotation, RecoversTheRotationOfAStretchedRotatedElement) {
  for (int k = 0; k < 20; ++k) {
    const Eigen::Matrix3d q = someRotation(0.3 * k - 2.5, Eigen::Vector3d(1.0, 0.2 * k, -0.5));
    Eigen::Matrix3d s;  // symmetric positive definite stretch
    s << 1.3, 0.1, -0.05, 0.1, 0.8, 0.02, -0.05, 0.02, 1.1;
    const Eigen::Matrix3d r = dc::extractRotation(q * s);
    expectProperRotation(r);
    EXPECT_NEAR((r - q).norm(), 0.0, 1e-10);
  }
}

TEST(Rotation, IdentityAtRest) {
  EXPECT_NEAR(
      (dc::extractRotation(Eigen::Matrix3d::Identity()) - Eigen::Matrix3d::Identity()).norm(), 0.0,
      1e-14);
}

TEST(Rotation, FlatElementsGetAProperRotation) {
  const Eigen::Matrix3d q = someRotation(1.1, Eigen::Vector3d(0.3, -1.0, 0.4));
  // Squashed flat along z, along a line, and to a point.
  expectProperRotation(dc::extractRotation(q * Eigen::Vector3d(1.0, 1.0, 0.0).asDiagonal()));
  expectProperRotation(dc::extractRotation(q * Eigen::Vector3d(2.0, 0.0, 0.0).asDiagonal()));
  expectProperRotation(dc::extractRotation(Eigen::Matrix3d::Zero()));
  // The flat element keeps the rotation of its plane.
  const Eigen::Matrix3d r = dc::extractRotation(q * Eigen::Vector3d(1.0, 0.9, 0.0).asDiagonal());
  EXPECT_NEAR((r - q).norm(), 0.0, 1e-10);
}

TEST(Rotation, InvertedElementsGetAProperRotation) {
  const Eigen::Matrix3d q = someRotation(-0.7, Eigen::Vector3d(1.0, 1.0, 1.0));
  // Inverted through z by a small amount: the closest proper rotation is q itself.
  const Eigen::Matrix3d f = q * Eigen::Vector3d(1.0, 0.95, -0.1).asDiagonal();
  ASSERT_LT(f.determinant(), 0.0);
  const Eigen::Matrix3d r = dc::extractRotation(f);
  expectProperRotation(r);
  EXPECT_NEAR((r - q).norm(), 0.0, 1e-10);
  // A mirror image (det F = -1) and a fully inverted element (F = -I) too.
  expectProperRotation(dc::extractRotation(Eigen::Vector3d(1.0, -1.0, 1.0).asDiagonal()));
  expectProperRotation(dc::extractRotation(-Eigen::Matrix3d::Identity()));
}

TEST(Rotation, NewtonIterationAgreesWithTheSvdOverStretchesRotationsAndShears) {
  // Random rotations times random stretches, from nearly rigid to strongly distorted, with
  // det F on both sides of where the SVD takes over.
  std::srand(7);
  int checked = 0;
  for (int k = 0; k < 2000; ++k) {
    const double spread = (k % 4 == 0) ? 1e-4 : (k % 4 == 1) ? 0.1 : (k % 4 == 2) ? 0.6 : 0.95;
    Eigen::Matrix3d f = someRotation(3.0 * Eigen::Vector3d::Random()(0), Eigen::Vector3d::Random());
    f *= Eigen::Matrix3d::Identity() + spread * Eigen::Matrix3d::Random();
    if (std::abs(f.determinant()) < 1e-6) continue;
    const Eigen::Matrix3d r = dc::extractRotation(f);
    expectProperRotation(r);
    EXPECT_NEAR((r - dc::extractRotationBySvd(f)).norm(), 0.0, 1e-11)
        << "F =\n"
        << f << "\ndet F = " << f.determinant();
    ++checked;
  }
  EXPECT_GT(checked, 1900);
}

TEST(Rotation, BatchesAgreeWithOneAtATimeAlsoWhenSomeNeedAnotherRoute) {
  // Batches of near-rotations mixed with inverted, flat and strongly stretched elements (which
  // leave the lockstep iteration), and batches shorter than kRotationBatch.
  std::srand(11);
  for (int k = 0; k < 500; ++k) {
    std::array<Eigen::Matrix3d, dc::kRotationBatch> f, r;
    const int count = 1 + k % dc::kRotationBatch;
    for (int l = 0; l < count; ++l) {
      const int kind = (k + 3 * l) % 7;
      const double spread = kind == 0 ? 0.9 : kind == 1 ? 0.3 : kind == 2 ? 1e-6 : 1e-3;
      f[l] = someRotation(3.0 * Eigen::Vector3d::Random()(0), Eigen::Vector3d::Random()) *
             (Eigen::Matrix3d::Identity() + spread * Eigen::Matrix3d::Random());
      if (kind == 3) f[l].col(2) *= -0.2;    // inverted
      if (kind == 4) f[l].col(1).setZero();  // flat
    }
    dc::extractRotations(f.data(), r.data(), count);
    for (int l = 0; l < count; ++l) {
      expectProperRotation(r[l]);
      EXPECT_NEAR((r[l] - dc::extractRotation(f[l])).norm(), 0.0, 1e-13) << "F =\n" << f[l];
    }
  }
}
