#include "deformable_sim/core/previous_solutions.h"

#include <Eigen/Cholesky>

namespace deformable_sim::core {

void PreviousSolutions::reserve(int capacity, int size) {
  solutions_.setZero(size, capacity);
  right_hand_sides_.setZero(size, capacity);
  gram_.setZero(capacity, capacity);
  system_.setZero(capacity, capacity);
  fit_.setZero(capacity);
  combination_.setZero(size);
  count_ = 0;
  next_ = 0;
}

bool PreviousSolutions::guess(const Eigen::VectorXd& b,
                              const std::vector<std::uint8_t>& constrained, Eigen::VectorXd& x) {
  const int m = count_;
  if (m == 0) return false;
  auto fit = fit_.head(m);
  fit.noalias() = right_hand_sides_.leftCols(m).transpose() * b;
  // Normal equations of min |b - B alpha|: B^T B is singular or nearly so when the right-hand
  // sides repeat (a body at rest); a shift of 1e-14 of its largest entry keeps it definite and
  // leaves out only directions that could not lower the residual below the solver's tolerance.
  auto system = system_.topLeftCorner(m, m);
  system = gram_.topLeftCorner(m, m);
  const double largest = system.diagonal().maxCoeff();
  if (!(largest > 0.0)) return false;
  system.diagonal().array() += 1e-14 * largest;
  Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> cholesky(system);
  if (cholesky.info() != Eigen::Success) return false;
  cholesky.solveInPlace(fit);
  combination_.noalias() = solutions_.leftCols(m) * fit;
  if (!combination_.allFinite()) return false;
  for (size_t i = 0; i < constrained.size(); ++i) {
    if (!constrained[i]) x.segment<3>(3 * i) = combination_.segment<3>(3 * i);
  }
  return true;
}

void PreviousSolutions::add(const Eigen::VectorXd& x, const Eigen::VectorXd& b,
                            const std::vector<std::uint8_t>& constrained) {
  if (capacity() == 0 || !(b.squaredNorm() > 0.0) || !b.allFinite() || !x.allFinite()) return;
  const int slot = next_;
  next_ = (next_ + 1) % capacity();
  if (count_ < capacity()) ++count_;
  auto solution = solutions_.col(slot);
  solution = x;
  for (size_t i = 0; i < constrained.size(); ++i) {
    if (constrained[i]) solution.segment<3>(3 * i).setZero();
  }
  right_hand_sides_.col(slot) = b;
  // The new row and column of the Gram matrix.
  auto column = fit_.head(count_);
  column.noalias() = right_hand_sides_.leftCols(count_).transpose() * b;
  gram_.col(slot).head(count_) = column;
  gram_.row(slot).head(count_) = column.transpose();
}

}  // namespace deformable_sim::core
