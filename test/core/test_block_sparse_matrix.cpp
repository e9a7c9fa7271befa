// The 3x3-block sparse matrix: its pattern (sorted, deduplicated, symmetric with transposes
// found), its products against the same matrix made dense, and the row-range product the
// solver's threads share.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <random>
#include <vector>

#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/elements/mesh.h"
#include "deformable_sim/core/solvers/block_sparse_matrix.h"

namespace dc = deformable_sim::core;

namespace {

// Five nodes: a chain 0-1-2-3 and node 4 joined to 0 and 3, each row unsorted and repeated.
std::vector<std::vector<int>> ringNeighbours() {
  return {{1, 0, 4, 1}, {2, 1, 0}, {3, 1, 2, 2}, {4, 2, 3}, {3, 0, 4, 4, 0}};
}

// Fills every stored block with a random 3x3 whose transpose is stored at (j, i): symmetric.
void fillSymmetric(dc::BlockSparseMatrix& a, std::mt19937& random) {
  std::uniform_real_distribution<double> entry(-1.0, 1.0);
  const std::vector<int>& transpose = a.transposeIndex();
  for (int s = 0; s < a.numBlocks(); ++s) {
    if (transpose[s] < s) continue;
    Eigen::Matrix3d block;
    for (int e = 0; e < 9; ++e) block(e / 3, e % 3) = entry(random);
    if (transpose[s] == s) block = (block + block.transpose()).eval();
    a.blocks()[s] = block;
    a.blocks()[transpose[s]] = block.transpose();
  }
}

Eigen::VectorXd randomVector(int size, std::mt19937& random) {
  std::uniform_real_distribution<double> entry(-1.0, 1.0);
  Eigen::VectorXd v(size);
  for (int i = 0; i < size; ++i) v[i] = entry(random);
  return v;
}

}  // namespace

TEST(BlockSparseMatrix, PatternIsSortedWithoutRepeatsAndStartsAtZero) {
  const dc::BlockSparseMatrix a(ringNeighbours());
  ASSERT_EQ(a.numBlockRows(), 5);
  EXPECT_EQ(a.rowStart(), (std::vector<int>{0, 3, 6, 9, 12, 15}));
  EXPECT_EQ(a.columns(), (std::vector<int>{0, 1, 4, 0, 1, 2, 1, 2, 3, 2, 3, 4, 0, 3, 4}));
  EXPECT_EQ(a.numBlocks(), 15);
  for (const Eigen::Matrix3d& block : a.blocks()) EXPECT_TRUE(block.isZero(0.0));
  EXPECT_TRUE(a.toDense().isZero(0.0));
  EXPECT_EQ(a.toDense().rows(), 15);
}

TEST(BlockSparseMatrix, BlockIndexFindsEveryStoredBlockAndOnlyThose) {
  const std::vector<std::vector<int>> neighbours = ringNeighbours();
  const dc::BlockSparseMatrix a(neighbours);
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 5; ++j) {
      bool stored = false;
      for (int k : neighbours[i]) stored = stored || k == j;
      const int index = a.blockIndex(i, j);
      if (!stored) {
        EXPECT_EQ(index, -1) << i << " " << j;
        continue;
      }
      ASSERT_GE(index, a.rowStart()[i]) << i << " " << j;
      ASSERT_LT(index, a.rowStart()[i + 1]) << i << " " << j;
      EXPECT_EQ(a.columns()[index], j);
    }
    EXPECT_EQ(a.diagonalIndex(i), a.blockIndex(i, i));
  }
}

TEST(BlockSparseMatrix, TransposeIndexPairsEachBlockWithItsMirror) {
  const dc::Mesh mesh = dc::makeBoxMesh({0, 0, 0}, {0.3, 0.2, 0.1}, {3, 2, 1});
  const dc::BlockSparseMatrix a(dc::nodeNeighbours(mesh));
  const std::vector<int>& transpose = a.transposeIndex();
  ASSERT_EQ(static_cast<int>(transpose.size()), a.numBlocks());
  for (int i = 0; i < a.numBlockRows(); ++i) {
    for (int s = a.rowStart()[i]; s < a.rowStart()[i + 1]; ++s) {
      const int t = transpose[s];
      ASSERT_GE(t, 0);
      const int j = a.columns()[s];
      // Block t is (j, i): in row j, column i; and its own transpose is s.
      EXPECT_GE(t, a.rowStart()[j]);
      EXPECT_LT(t, a.rowStart()[j + 1]);
      EXPECT_EQ(a.columns()[t], i);
      EXPECT_EQ(transpose[t], s);
      if (i == j) {
        EXPECT_EQ(t, s);
      }
    }
  }
}

TEST(BlockSparseMatrix, DenseCopyPutsEachBlockWhereItsIndicesSay) {
  dc::BlockSparseMatrix a(ringNeighbours());
  Eigen::Matrix3d block;
  block << 1, 2, 3, 4, 5, 6, 7, 8, 9;
  a.blocks()[a.blockIndex(4, 0)] = block;
  a.blocks()[a.diagonalIndex(2)] = -block;
  const Eigen::MatrixXd dense = a.toDense();
  EXPECT_EQ(Eigen::Matrix3d(dense.block<3, 3>(12, 0)), block);
  EXPECT_EQ(Eigen::Matrix3d(dense.block<3, 3>(6, 6)), Eigen::Matrix3d(-block));
  EXPECT_EQ(dense.cwiseAbs().sum(), 2.0 * block.cwiseAbs().sum());
  a.setZero();
  EXPECT_TRUE(a.toDense().isZero(0.0));
}

TEST(BlockSparseMatrix, MultiplyAgreesWithTheDenseMatrix) {
  std::mt19937 random(11);
  const dc::Mesh mesh = dc::makeBoxMesh({0, 0, 0}, {0.3, 0.2, 0.2}, {3, 2, 2});
  dc::BlockSparseMatrix a(dc::nodeNeighbours(mesh));
  fillSymmetric(a, random);
  const Eigen::MatrixXd dense = a.toDense();
  EXPECT_TRUE(dense == dense.transpose());
  const Eigen::VectorXd x = randomVector(3 * a.numBlockRows(), random);
  Eigen::VectorXd y(x.size());
  a.multiply(x, y);
  EXPECT_LE((y - dense * x).norm(), 1e-13 * (dense.norm() * x.norm()));
  // Symmetric: x^T (A z) = z^T (A x).
  const Eigen::VectorXd z = randomVector(x.size(), random);
  Eigen::VectorXd az(z.size());
  a.multiply(z, az);
  EXPECT_NEAR(x.dot(az), z.dot(y), 1e-12 * (dense.norm() * x.norm() * z.norm()));
}

TEST(BlockSparseMatrix, RowRangeProductScalesAddsTheDiagonalAndLeavesOtherRowsAlone) {
  std::mt19937 random(5);
  const dc::Mesh mesh = dc::makeBoxMesh({0, 0, 0}, {0.2, 0.2, 0.1}, {2, 2, 1});
  dc::BlockSparseMatrix a(dc::nodeNeighbours(mesh));
  fillSymmetric(a, random);
  const int n = a.numBlockRows();
  const Eigen::VectorXd x = randomVector(3 * n, random);
  Eigen::VectorXd d(n);
  for (int i = 0; i < n; ++i) d[i] = 1.0 + i;  // a lumped mass per node
  const double scale = 0.25, diagonal_scale = 3.0;
  Eigen::MatrixXd expected_matrix = scale * a.toDense();
  for (int i = 0; i < n; ++i) {
    expected_matrix.block<3, 3>(3 * i, 3 * i) +=
        diagonal_scale * d[i] * Eigen::Matrix3d::Identity();
  }
  const Eigen::VectorXd expected = expected_matrix * x;
  const int begin = 2, end = n - 3;
  Eigen::VectorXd y = Eigen::VectorXd::Constant(3 * n, 42.0);
  a.multiplyRows(begin, end, x.data(), y.data(), scale, d.data(), diagonal_scale);
  for (int k = 0; k < 3 * n; ++k) {
    if (k < 3 * begin || k >= 3 * end) {
      EXPECT_EQ(y[k], 42.0) << k;
    } else {
      EXPECT_NEAR(y[k], expected[k], 1e-13 * expected.lpNorm<Eigen::Infinity>()) << k;
    }
  }
  // Without a diagonal the default is the plain product.
  Eigen::VectorXd plain(3 * n);
  a.multiplyRows(0, n, x.data(), plain.data());
  EXPECT_LE((plain - a.toDense() * x).norm(), 1e-13 * x.norm() * a.toDense().norm());
}

TEST(BlockSparseMatrix, RowsSplitAnyWayGiveTheSameBitsAsOneCall) {
  // What lets the solver's threads share a product: each row's sum does not depend on which call
  // (which thread) computes it.
  std::mt19937 random(3);
  const dc::Mesh mesh = dc::makeBoxMesh({0, 0, 0}, {0.4, 0.3, 0.2}, {4, 3, 2});
  dc::BlockSparseMatrix a(dc::nodeNeighbours(mesh));
  fillSymmetric(a, random);
  for (Eigen::Matrix3d& block : a.blocks()) block *= 1e6;  // large terms that cancel
  const int n = a.numBlockRows();
  const Eigen::VectorXd x = randomVector(3 * n, random);
  Eigen::VectorXd d(n);
  for (int i = 0; i < n; ++i) d[i] = 0.5 + 0.01 * i;
  Eigen::VectorXd whole(3 * n);
  a.multiplyRows(0, n, x.data(), whole.data(), 0.7, d.data(), 2.0);
  for (int pieces : {2, 3, 7}) {
    Eigen::VectorXd split(3 * n);
    for (int p = 0; p < pieces; ++p) {
      a.multiplyRows(p * n / pieces, (p + 1) * n / pieces, x.data(), split.data(), 0.7, d.data(),
                     2.0);
    }
    EXPECT_EQ(split, whole) << pieces << " pieces";
  }
}
