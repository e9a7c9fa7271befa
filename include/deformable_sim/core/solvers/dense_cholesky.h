// A small symmetric positive definite system kept dense: A = L L^T, factorized by Eigen and
// solved by two sweeps of column updates over L and L^T (both stored column by column, so every
// sweep reads contiguous memory and vectorizes; with AVX2 and FMA, four wide). For the coarse
// level of the two-level preconditioner, solved once per CG iteration: there Eigen's own
// triangular solves, compiled for the x86-64 baseline, took a fifth of a small body's step.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace deformable_sim::core {

class DenseCholesky {
 public:
  /// Sizes the matrix (zero) and the factor's storage: later calls allocate nothing.
  void resize(int size);
  int size() const { return static_cast<int>(matrix_.rows()); }

  /// The matrix to fill before factorize(): only its lower triangle is read.
  Eigen::MatrixXd& matrix() { return matrix_; }

  /// Factorizes the lower triangle of matrix(); false if it is not positive definite.
  bool factorize();

  /// x = A^-1 b with the last factorization (x may be b).
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;

 private:
  Eigen::MatrixXd matrix_;
  Eigen::LLT<Eigen::MatrixXd> factor_;
  Eigen::MatrixXd upper_;             ///< L^T, so that the backward sweep reads its columns
  Eigen::VectorXd inverse_diagonal_;  ///< 1 / L_jj
};

}  // namespace deformable_sim::core
