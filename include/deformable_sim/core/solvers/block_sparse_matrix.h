// A square matrix of 3x3 blocks in compressed-row form, with a fixed pattern: built once from the
// element connectivity (core/elements/mesh.h nodeNeighbours), then filled in place every step
// through precomputed block indices.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace deformable_sim::core {

class BlockSparseMatrix {
 public:
  BlockSparseMatrix() = default;

  /// Pattern with a block (i, j) for every j in neighbours[i] (in any order, repeats allowed;
  /// i itself among them, and i in neighbours[j] too), both triangles stored. All blocks start
  /// at zero.
  explicit BlockSparseMatrix(std::vector<std::vector<int>> neighbours);

  int numBlockRows() const { return static_cast<int>(row_start_.size()) - 1; }
  int numBlocks() const { return static_cast<int>(blocks_.size()); }

  /// Index of block (row, col) in blocks(), or -1 if it is not in the pattern. A binary search:
  /// for set-up, not for the step.
  int blockIndex(int row, int col) const;
  int diagonalIndex(int row) const { return diagonal_[row]; }
  /// Per block (i, j): the index of block (j, i) (the pattern is symmetric).
  const std::vector<int>& transposeIndex() const { return transpose_; }

  const std::vector<int>& rowStart() const { return row_start_; }
  const std::vector<int>& columns() const { return columns_; }
  std::vector<Eigen::Matrix3d>& blocks() { return blocks_; }
  const std::vector<Eigen::Matrix3d>& blocks() const { return blocks_; }

  void setZero();

  /// y = A x (x and y of size 3 * numBlockRows(); y must not alias x).
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;

  /// Rows begin .. end - 1 of y = scale A x + diagonal_scale D x, into y[3 begin] ..
  /// y[3 end - 1] (x and y: the whole vectors' entries; D: one number per node, or none if
  /// null). The products' inner loop: with AVX2 and FMA (checked once, at run time) four-wide
  /// fused multiply-adds, otherwise plain Eigen. Each row sums its blocks in the same order on
  /// every call, whichever thread makes it.
  void multiplyRows(int begin, int end, const double* x, double* y, double scale = 1.0,
                    const double* diagonal = nullptr, double diagonal_scale = 0.0) const;

  /// The same matrix as a dense one (for tests and small diagnostics).
  Eigen::MatrixXd toDense() const;

 private:
  std::vector<int> row_start_{0};
  std::vector<int> columns_;
  std::vector<int> diagonal_;
  std::vector<int> transpose_;
  std::vector<Eigen::Matrix3d> blocks_;
};

}  // namespace deformable_sim::core
