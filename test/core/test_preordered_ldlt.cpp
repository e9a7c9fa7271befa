// The sparse LDL^T kept in a fill-reducing order: where each entry's value is stored, solves in
// the caller's order against dense references, the shift, refactorizing in place, the fill the
// ordering saves, and what it reports for a singular matrix.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <set>
#include <utility>
#include <vector>

#include "deformable_sim/core/solvers/preordered_ldlt.h"

namespace dc = deformable_sim::core;

namespace {

// A symmetric matrix in the form the class takes: every (row, column) of its pattern once, both
// triangles, and the dense matrix with those entries.
struct SymmetricMatrix {
  int size = 0;
  std::vector<std::pair<int, int>> entries;
  Eigen::MatrixXd dense;
};

// The five-point Laplacian of an nx x ny grid plus `diagonal` on the diagonal.
SymmetricMatrix gridLaplacian(int nx, int ny, double diagonal) {
  SymmetricMatrix a;
  a.size = nx * ny;
  a.dense = Eigen::MatrixXd::Zero(a.size, a.size);
  auto node = [nx](int i, int j) { return i + nx * j; };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int p = node(i, j);
      a.dense(p, p) = 4.0 + diagonal;
      if (i + 1 < nx) a.dense(p, node(i + 1, j)) = a.dense(node(i + 1, j), p) = -1.0;
      if (j + 1 < ny) a.dense(p, node(i, j + 1)) = a.dense(node(i, j + 1), p) = -1.0;
    }
  }
  for (int c = 0; c < a.size; ++c) {
    for (int r = 0; r < a.size; ++r) {
      if (a.dense(r, c) != 0.0) a.entries.emplace_back(r, c);
    }
  }
  return a;
}

// Writes `dense`'s values through the indices setPattern returned.
void writeValues(dc::PreorderedLdlt& ldlt, const SymmetricMatrix& a, const Eigen::MatrixXd& dense,
                 const std::vector<int>& value_of_entry) {
  ldlt.setZero();
  for (size_t k = 0; k < a.entries.size(); ++k) {
    if (value_of_entry[k] >= 0) {
      ldlt.values()[value_of_entry[k]] = dense(a.entries[k].first, a.entries[k].second);
    }
  }
}

// Gives `ldlt` a's pattern and values; returns where each entry's value went.
std::vector<int> load(dc::PreorderedLdlt& ldlt, const SymmetricMatrix& a) {
  const std::vector<int> value_of_entry = ldlt.setPattern(a.size, a.entries);
  writeValues(ldlt, a, a.dense, value_of_entry);
  return value_of_entry;
}

Eigen::VectorXd ramp(int size) {
  Eigen::VectorXd b(size);
  for (int i = 0; i < size; ++i) b[i] = 1.0 + 0.37 * i - 0.01 * i * i;
  return b;
}

}  // namespace

TEST(PreorderedLdlt, EachSymmetricPairOfEntriesHasOneStoredValue) {
  const SymmetricMatrix a = gridLaplacian(5, 4, 0.0);
  dc::PreorderedLdlt ldlt;
  const std::vector<int> value_of_entry = ldlt.setPattern(a.size, a.entries);
  ASSERT_EQ(value_of_entry.size(), a.entries.size());
  std::set<std::pair<int, int>> entries(a.entries.begin(), a.entries.end());
  std::set<int> values;
  int off_diagonal = 0;
  for (size_t k = 0; k < a.entries.size(); ++k) {
    const auto [row, column] = a.entries[k];
    if (row == column) {
      EXPECT_GE(value_of_entry[k], 0) << "diagonal " << row;
    } else {
      ++off_diagonal;
      // Exactly one of (row, column) and (column, row) holds the value.
      const auto partner =
          std::find(a.entries.begin(), a.entries.end(), std::make_pair(column, row)) -
          a.entries.begin();
      ASSERT_LT(static_cast<size_t>(partner), a.entries.size());
      EXPECT_NE(value_of_entry[k] >= 0, value_of_entry[partner] >= 0) << row << " " << column;
    }
    if (value_of_entry[k] >= 0) {
      EXPECT_TRUE(values.insert(value_of_entry[k]).second)
          << "value " << value_of_entry[k] << " shared";
    }
  }
  // One value per diagonal entry and per pair: the stored triangle, numbered 0 .. count - 1.
  EXPECT_EQ(static_cast<int>(values.size()), a.size + off_diagonal / 2);
  EXPECT_EQ(*values.begin(), 0);
  EXPECT_EQ(*values.rbegin(), static_cast<int>(values.size()) - 1);
}

TEST(PreorderedLdlt, SolvesInTheCallersOrderAsTheDenseMatrixDoes) {
  const SymmetricMatrix a = gridLaplacian(6, 5, 0.1);
  dc::PreorderedLdlt ldlt;
  const std::vector<int> value_of_entry = load(ldlt, a);
  ASSERT_TRUE(ldlt.factorize());
  const Eigen::VectorXd b = ramp(a.size);
  Eigen::VectorXd x(a.size);
  ldlt.solve(b, x);
  const Eigen::VectorXd expected = a.dense.llt().solve(b);
  EXPECT_LE((x - expected).norm(), 1e-12 * expected.norm());
  EXPECT_LE((a.dense * x - b).norm(), 1e-12 * b.norm());
}

TEST(PreorderedLdlt, TheShiftAddsToEveryDiagonalEntry) {
  const SymmetricMatrix a = gridLaplacian(4, 4, 0.0);
  dc::PreorderedLdlt ldlt;
  const std::vector<int> value_of_entry = load(ldlt, a);
  const double shift = 2.5;
  ASSERT_TRUE(ldlt.factorize(shift));
  const Eigen::VectorXd b = ramp(a.size);
  Eigen::VectorXd x(a.size);
  ldlt.solve(b, x);
  const Eigen::MatrixXd shifted = a.dense + shift * Eigen::MatrixXd::Identity(a.size, a.size);
  EXPECT_LE((shifted * x - b).norm(), 1e-13 * b.norm());
  EXPECT_GT((a.dense * x - b).norm(), 0.1 * b.norm());  // not the unshifted solution
  // The stored values are left as written: without the shift, the plain matrix again.
  ASSERT_TRUE(ldlt.factorize());
  ldlt.solve(b, x);
  EXPECT_LE((a.dense * x - b).norm(), 1e-12 * b.norm());
}

TEST(PreorderedLdlt, RefactorizingWithNewValuesSolvesTheNewMatrix) {
  const SymmetricMatrix a = gridLaplacian(5, 3, 0.0);
  dc::PreorderedLdlt ldlt;
  const std::vector<int> value_of_entry = load(ldlt, a);
  ASSERT_TRUE(ldlt.factorize());
  // Same pattern, other values: the off-diagonal couplings halved, the diagonal weighted.
  Eigen::MatrixXd second = 0.5 * a.dense;
  for (int i = 0; i < a.size; ++i) second(i, i) = 3.0 + 0.1 * i;
  writeValues(ldlt, a, second, value_of_entry);
  ASSERT_TRUE(ldlt.factorize());
  const Eigen::VectorXd b = ramp(a.size);
  Eigen::VectorXd x(a.size);
  ldlt.solve(b, x);
  EXPECT_LE((second * x - b).norm(), 1e-13 * b.norm());
}

TEST(PreorderedLdlt, TheOrderingAvoidsTheFillOfAnArrowMatrix) {
  // A star: node 0 coupled to every other node. Eliminated in the given order, node 0 first, it
  // fills the whole factor; eliminated leaves first (what a minimum-degree order does), the
  // factor keeps just the n - 1 couplings.
  const int n = 40;
  SymmetricMatrix a;
  a.size = n;
  a.dense = Eigen::MatrixXd::Identity(n, n) * 2.0;
  a.dense(0, 0) = n;
  for (int i = 1; i < n; ++i) {
    a.dense(0, i) = a.dense(i, 0) = 1.0;
    a.entries.emplace_back(0, i);
    a.entries.emplace_back(i, 0);
  }
  for (int i = 0; i < n; ++i) a.entries.emplace_back(i, i);
  dc::PreorderedLdlt ldlt;
  const std::vector<int> value_of_entry = ldlt.setPattern(n, a.entries);
  EXPECT_EQ(ldlt.factorNonZeros(), n - 1);
  writeValues(ldlt, a, a.dense, value_of_entry);
  ASSERT_TRUE(ldlt.factorize());
  const Eigen::VectorXd b = ramp(n);
  Eigen::VectorXd x(n);
  ldlt.solve(b, x);
  EXPECT_LE((a.dense * x - b).norm(), 1e-13 * b.norm());
}

TEST(PreorderedLdlt, AZeroPivotIsReportedAndAShiftCuresIt) {
  // [1 1; 1 1] is singular: its second pivot is exactly 1 - 1 * 1 = 0 in either order.
  SymmetricMatrix a;
  a.size = 2;
  a.dense = Eigen::MatrixXd::Ones(2, 2);
  a.entries = {{0, 0}, {0, 1}, {1, 0}, {1, 1}};
  dc::PreorderedLdlt ldlt;
  const std::vector<int> value_of_entry = ldlt.setPattern(2, a.entries);
  writeValues(ldlt, a, a.dense, value_of_entry);
  EXPECT_FALSE(ldlt.factorize());
  ASSERT_TRUE(ldlt.factorize(1.0));
  Eigen::VectorXd x(2);
  ldlt.solve(Eigen::Vector2d(3.0, 1.0), x);
  // (A + I)^-1 (3, 1) = (5/3, -1/3).
  EXPECT_NEAR(x[0], 5.0 / 3.0, 1e-15);
  EXPECT_NEAR(x[1], -1.0 / 3.0, 1e-15);
}

// An LDL^T only fails on an exact zero pivot: an indefinite, nonsingular matrix factorizes, and
// factorize() must still say it is not positive definite.
TEST(PreorderedLdlt, AnIndefiniteMatrixIsReportedAsNotDefinite) {
  SymmetricMatrix a;
  a.size = 2;
  a.dense = Eigen::Matrix2d(Eigen::Vector2d(1.0, -1.0).asDiagonal());
  a.entries = {{0, 0}, {1, 1}};
  dc::PreorderedLdlt ldlt;
  const std::vector<int> value_of_entry = ldlt.setPattern(2, a.entries);
  writeValues(ldlt, a, a.dense, value_of_entry);
  EXPECT_FALSE(ldlt.factorize());
}
