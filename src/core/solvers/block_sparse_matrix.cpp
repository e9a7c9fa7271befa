#include "deformable_sim/core/solvers/block_sparse_matrix.h"

#include <algorithm>

#include "deformable_sim/core/base/cpu_features.h"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace deformable_sim::core {

namespace {

// The arguments of multiplyRows.
struct Rows {
  const int* row_start;
  const int* columns;
  const Eigen::Matrix3d* blocks;
  int begin, end;
  const double* x;
  double* y;
  double scale;
  const double* diagonal;
  double diagonal_scale;
};

void multiplyRowsPortable(const Rows& a) {
  for (int i = a.begin; i < a.end; ++i) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int s = a.row_start[i]; s < a.row_start[i + 1]; ++s) {
      sum.noalias() += a.blocks[s] * Eigen::Map<const Eigen::Vector3d>(a.x + 3 * a.columns[s]);
    }
    sum *= a.scale;
    if (a.diagonal)
      sum += (a.diagonal_scale * a.diagonal[i]) * Eigen::Map<const Eigen::Vector3d>(a.x + 3 * i);
    Eigen::Map<Eigen::Vector3d>(a.y + 3 * i) = sum;
  }
}

#if defined(__x86_64__)
// A block is stored column-major (9 doubles): its columns are read four-wide from entries 0, 3
// and 5 (the last rotated down one lane), so that no load leaves the block; the fourth lane is
// ignored. Each block's product is formed whole and then added to the row's sum, as the portable
// loop does: summing column by column instead leaves the large terms of a stiff body's rigid
// motions to cancel at the end, and a steel cube spinning at dt = 1/30 s then gains 2e-7 of its
// energy (test_hard_cases).
__attribute__((target("avx2,fma"))) void multiplyRowsAvx2(const Rows& a) {
  const __m256d scale = _mm256_set1_pd(a.scale);
  const __m256i first_three = _mm256_setr_epi64x(-1, -1, -1, 0);
  for (int i = a.begin; i < a.end; ++i) {
    __m256d sum = _mm256_setzero_pd();
    for (int s = a.row_start[i]; s < a.row_start[i + 1]; ++s) {
      const double* p = a.blocks[s].data();
      const double* xp = a.x + 3 * a.columns[s];
      __m256d t = _mm256_mul_pd(_mm256_loadu_pd(p), _mm256_broadcast_sd(xp));
      t = _mm256_fmadd_pd(_mm256_loadu_pd(p + 3), _mm256_broadcast_sd(xp + 1), t);
      t = _mm256_fmadd_pd(_mm256_permute4x64_pd(_mm256_loadu_pd(p + 5), 0x39),
                          _mm256_broadcast_sd(xp + 2), t);
      sum = _mm256_add_pd(sum, t);
    }
    sum = _mm256_mul_pd(sum, scale);
    if (a.diagonal) {
      const __m256d own = _mm256_maskload_pd(a.x + 3 * i, first_three);  // x_i, not x_i+1
      sum =
          _mm256_add_pd(sum, _mm256_mul_pd(_mm256_set1_pd(a.diagonal_scale * a.diagonal[i]), own));
    }
    _mm256_maskstore_pd(a.y + 3 * i, first_three, sum);
  }
}

const bool kHasAvx2Fma = hasAvx2Fma();
#endif

}  // namespace

BlockSparseMatrix::BlockSparseMatrix(std::vector<std::vector<int>> neighbours) {
  const int num_nodes = static_cast<int>(neighbours.size());
  row_start_.assign(1, 0);
  diagonal_.resize(num_nodes);
  for (int i = 0; i < num_nodes; ++i) {
    std::vector<int>& row = neighbours[i];
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    for (int j : row) {
      if (j == i) diagonal_[i] = static_cast<int>(columns_.size());
      columns_.push_back(j);
    }
    row_start_.push_back(static_cast<int>(columns_.size()));
  }
  blocks_.assign(columns_.size(), Eigen::Matrix3d::Zero());
  transpose_.resize(columns_.size());
  for (int i = 0; i < num_nodes; ++i) {
    for (int s = row_start_[i]; s < row_start_[i + 1]; ++s)
      transpose_[s] = blockIndex(columns_[s], i);
  }
}

int BlockSparseMatrix::blockIndex(int row, int col) const {
  const auto begin = columns_.begin() + row_start_[row];
  const auto end = columns_.begin() + row_start_[row + 1];
  const auto it = std::lower_bound(begin, end, col);
  return (it != end && *it == col) ? static_cast<int>(it - columns_.begin()) : -1;
}

void BlockSparseMatrix::setZero() {
  for (Eigen::Matrix3d& block : blocks_) block.setZero();
}

void BlockSparseMatrix::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  multiplyRows(0, numBlockRows(), x.data(), y.data());
}

void BlockSparseMatrix::multiplyRows(int begin, int end, const double* x, double* y, double scale,
                                     const double* diagonal, double diagonal_scale) const {
  const Rows rows{row_start_.data(), columns_.data(), blocks_.data(), begin, end, x, y, scale,
                  diagonal,          diagonal_scale};
#if defined(__x86_64__)
  if (kHasAvx2Fma) {
    multiplyRowsAvx2(rows);
    return;
  }
#endif
  multiplyRowsPortable(rows);
}

Eigen::MatrixXd BlockSparseMatrix::toDense() const {
  const int n = numBlockRows();
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  for (int i = 0; i < n; ++i) {
    for (int k = row_start_[i]; k < row_start_[i + 1]; ++k) {
      dense.block<3, 3>(3 * i, 3 * columns_[k]) = blocks_[k];
    }
  }
  return dense;
}

}  // namespace deformable_sim::core
