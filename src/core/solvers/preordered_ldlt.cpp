#include "deformable_sim/core/solvers/preordered_ldlt.h"

#include <Eigen/OrderingMethods>

namespace deformable_sim::core {

std::vector<int> PreorderedLdlt::setPattern(int size,
                                            const std::vector<std::pair<int, int>>& entries) {
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(entries.size());
  for (const auto& [row, column] : entries) triplets.emplace_back(row, column, 1.0);
  Eigen::SparseMatrix<double> pattern(size, size);
  pattern.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> ordering;
  Eigen::AMDOrdering<int>()(pattern, ordering);
  const Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse = ordering.inverse();
  permutation_.assign(inverse.indices().data(), inverse.indices().data() + size);

  // The permuted upper triangle, each value tagged with its entry's number to find where it went.
  triplets.clear();
  for (size_t k = 0; k < entries.size(); ++k) {
    const int row = permutation_[entries[k].first];
    const int column = permutation_[entries[k].second];
    if (row <= column) triplets.emplace_back(row, column, 1.0 + static_cast<double>(k));
  }
  matrix_.resize(size, size);
  matrix_.setFromTriplets(triplets.begin(), triplets.end());
  matrix_.makeCompressed();
  std::vector<int> value_of_entry(entries.size(), -1);
  for (int v = 0; v < matrix_.nonZeros(); ++v) {
    value_of_entry[static_cast<size_t>(matrix_.valuePtr()[v]) - 1] = v;
  }
  factorization_.analyzePattern(matrix_);
  permuted_rhs_.resize(size);
  permuted_solution_.resize(size);
  return value_of_entry;
}

bool PreorderedLdlt::factorize(double shift) {
  factorization_.setShift(shift);
  factorization_.refactorize(matrix_);
  // LDL^T only fails on an exact zero pivot; a matrix that is not positive definite (or NaN)
  // shows in D.
  return factorization_.info() == Eigen::Success && factorization_.pivotsPositive();
}

void PreorderedLdlt::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  const int size = static_cast<int>(permutation_.size());
  for (int k = 0; k < size; ++k) permuted_rhs_[permutation_[k]] = b[k];
  permuted_solution_ = factorization_.solve(permuted_rhs_);
  for (int k = 0; k < size; ++k) x[k] = permuted_solution_[permutation_[k]];
}

}  // namespace deformable_sim::core
