// A symmetric sparse matrix kept in a fill-reducing order and its LDL^T, refactorized in place.
// Eigen's SimplicialLDLT::factorize builds a temporary copy of the matrix on every call; here the
// matrix is stored already permuted (AMD, computed once from its pattern), upper triangle only,
// so that refactorizing and solving allocate nothing after the pattern is set, up to 16 384
// unknowns: above that, Eigen takes the factorization's work vectors (over its 128 KB stack
// limit) from the heap.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <utility>
#include <vector>

namespace deformable_sim::core {

class PreorderedLdlt {
 public:
  /// The pattern: every (row, column) of the full symmetric matrix, each once. Returns, per entry,
  /// the index of its value in values(), or -1 where its symmetric partner holds the value.
  std::vector<int> setPattern(int size, const std::vector<std::pair<int, int>>& entries);

  /// The stored values (upper triangle in the fill-reducing order), to be written through the
  /// indices setPattern returned.
  double* values() { return matrix_.valuePtr(); }
  void setZero() { std::fill(matrix_.valuePtr(), matrix_.valuePtr() + matrix_.nonZeros(), 0.0); }

  /// Entries of the factor L below its diagonal (known once the pattern is set).
  int factorNonZeros() const { return factorization_.nonZeros(); }

  /// Factorizes A + shift I for the values written; false if it is not positive definite.
  bool factorize(double shift = 0.0);

  /// x = A^-1 b in the original order of the unknowns (x must not alias b).
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);

 private:
  class Factorization : public Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Upper,
                                                     Eigen::NaturalOrdering<int>> {
   public:
    void refactorize(const Eigen::SparseMatrix<double>& upper) {
      factorize_preordered<true>(upper);
    }
    int nonZeros() const { return static_cast<int>(m_matrix.nonZeros()); }
    /// D > 0 (vectorD() would return a copy).
    bool pivotsPositive() const { return (m_diag.array() > 0.0).all(); }
  };

  Eigen::SparseMatrix<double> matrix_;
  std::vector<int> permutation_;  ///< unknown -> its row in matrix_
  Factorization factorization_;
  Eigen::VectorXd permuted_rhs_, permuted_solution_;
};

}  // namespace deformable_sim::core
