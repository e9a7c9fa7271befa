#include "deformable_sim/core/block_sparse_matrix.h"

#include <algorithm>

namespace deformable_sim::core {

BlockSparseMatrix::BlockSparseMatrix(const Mesh& mesh) {
  const int num_nodes = mesh.numNodes();
  std::vector<std::vector<int>> neighbours(num_nodes);
  for (int i = 0; i < num_nodes; ++i) neighbours[i].push_back(i);
  for (const Tetrahedron& t : mesh.tetrahedra) {
    for (int a : t) {
      for (int b : t) neighbours[a].push_back(b);
    }
  }
  for (const Cell& c : mesh.cells) {
    for (int a = 0; a < c.size(); ++a) {
      for (int b = 0; b < c.size(); ++b) neighbours[c.nodes[a]].push_back(c.nodes[b]);
    }
  }
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
  const int n = numBlockRows();
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int k = row_start_[i]; k < row_start_[i + 1]; ++k) {
      sum.noalias() += blocks_[k] * x.segment<3>(3 * columns_[k]);
    }
    y.segment<3>(3 * i) = sum;
  }
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
