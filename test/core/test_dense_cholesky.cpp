// The dense Cholesky factorization of the coarse level: solves against closed-form inverses,
// reads only the lower triangle, refactorizes in place, and reports what is not positive
// definite.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

#include "deformable_sim/core/solvers/dense_cholesky.h"

namespace dc = deformable_sim::core;

namespace {

// The second-difference matrix tridiag(-1, 2, -1) of size n, lower triangle only.
void fillLaplacian(dc::DenseCholesky& cholesky, int n) {
  cholesky.resize(n);
  for (int i = 0; i < n; ++i) {
    cholesky.matrix()(i, i) = 2.0;
    if (i + 1 < n) cholesky.matrix()(i + 1, i) = -1.0;
  }
}

}  // namespace

TEST(DenseCholesky, ResizeGivesAZeroMatrixOfThatSize) {
  dc::DenseCholesky cholesky;
  EXPECT_EQ(cholesky.size(), 0);
  cholesky.resize(6);
  EXPECT_EQ(cholesky.size(), 6);
  EXPECT_EQ(cholesky.matrix().rows(), 6);
  EXPECT_EQ(cholesky.matrix().cols(), 6);
  EXPECT_TRUE(cholesky.matrix().isZero(0.0));
  // The zero matrix is not positive definite.
  EXPECT_FALSE(cholesky.factorize());
}

TEST(DenseCholesky, SolvesTheSecondDifferenceMatrixAsItsClosedFormInverse) {
  // (A^-1)_ij = min(i, j) (n + 1 - max(i, j)) / (n + 1) for 1-based i, j: each column of the
  // inverse is the solution for a unit right-hand side. Sizes on either side of the sweeps'
  // blocks of four columns.
  for (int n : {1, 2, 3, 4, 5, 7, 8, 11, 16, 17}) {
    dc::DenseCholesky cholesky;
    fillLaplacian(cholesky, n);
    ASSERT_TRUE(cholesky.factorize()) << n;
    for (int j = 0; j < n; ++j) {
      const Eigen::VectorXd e = Eigen::VectorXd::Unit(n, j);
      Eigen::VectorXd x(n);
      cholesky.solve(e, x);
      for (int i = 0; i < n; ++i) {
        const double expected = static_cast<double>(std::min(i, j) + 1) * (n - std::max(i, j)) /
                                static_cast<double>(n + 1);
        EXPECT_NEAR(x[i], expected, 1e-13 * n) << "n " << n << " (" << i << ", " << j << ")";
      }
    }
  }
}

TEST(DenseCholesky, ADiagonalMatrixDividesEachEntry) {
  dc::DenseCholesky cholesky;
  cholesky.resize(9);
  Eigen::VectorXd diagonal(9), b(9);
  for (int i = 0; i < 9; ++i) {
    diagonal[i] = std::pow(10.0, i - 4);  // 1e-4 .. 1e4: a wide spread of scales
    b[i] = 1.0 + 0.5 * i;
  }
  cholesky.matrix().diagonal() = diagonal;
  ASSERT_TRUE(cholesky.factorize());
  Eigen::VectorXd x(9);
  cholesky.solve(b, x);
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(x[i] * diagonal[i] / b[i], 1.0, 1e-15) << i;
}

TEST(DenseCholesky, TheUpperTriangleIsNeverRead) {
  const int n = 10;
  dc::DenseCholesky clean, dirty;
  fillLaplacian(clean, n);
  fillLaplacian(dirty, n);
  dirty.matrix().triangularView<Eigen::StrictlyUpper>().setConstant(
      std::numeric_limits<double>::quiet_NaN());
  ASSERT_TRUE(clean.factorize());
  ASSERT_TRUE(dirty.factorize());
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  Eigen::VectorXd x_clean(n), x_dirty(n);
  clean.solve(b, x_clean);
  dirty.solve(b, x_dirty);
  EXPECT_EQ(x_clean, x_dirty);
}

TEST(DenseCholesky, RefactorizingSolvesTheNewMatrix) {
  // A matrix of the same size filled again (the coarse operator of a later step): the solve must
  // use the new factor only, nothing left over from the first.
  const int n = 7;
  dc::DenseCholesky cholesky;
  fillLaplacian(cholesky, n);
  ASSERT_TRUE(cholesky.factorize());
  Eigen::MatrixXd second = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j <= i; ++j) second(i, j) = 1.0 / (1.0 + i + j);  // Hilbert-like, lower
    second(i, i) += 1.0;
  }
  cholesky.matrix() = second;
  const Eigen::MatrixXd full = second.selfadjointView<Eigen::Lower>();
  ASSERT_TRUE(cholesky.factorize());
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, 1.0, 3.0);
  Eigen::VectorXd x(n);
  cholesky.solve(b, x);
  EXPECT_LE((full * x - b).norm(), 1e-14 * b.norm());
  // And the solution may overwrite the right-hand side.
  Eigen::VectorXd in_place = b;
  cholesky.solve(in_place, in_place);
  EXPECT_EQ(in_place, x);
}

TEST(DenseCholesky, WhatIsNotPositiveDefiniteIsReported) {
  dc::DenseCholesky cholesky;
  // Negative definite.
  cholesky.resize(3);
  cholesky.matrix().diagonal().setConstant(-1.0);
  EXPECT_FALSE(cholesky.factorize());
  // Singular: [1 1; 1 1] has the null vector (1, -1).
  cholesky.resize(2);
  cholesky.matrix() << 1.0, 0.0, 1.0, 1.0;
  EXPECT_FALSE(cholesky.factorize());
  // Indefinite, the trouble deep in the matrix: the second difference with one sign flipped.
  fillLaplacian(cholesky, 6);
  cholesky.matrix()(4, 4) = -2.0;
  EXPECT_FALSE(cholesky.factorize());
}

// Eigen's LLT tests each pivot with `x <= 0`, which a NaN passes: a matrix with a NaN on its
// diagonal must still be refused, or every solve returns NaN.
TEST(DenseCholesky, ANotANumberIsNotPositiveDefinite) {
  dc::DenseCholesky cholesky;
  fillLaplacian(cholesky, 3);
  cholesky.matrix()(1, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(cholesky.factorize());
}
