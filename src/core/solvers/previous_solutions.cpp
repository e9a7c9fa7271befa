#include "deformable_sim/core/solvers/previous_solutions.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "deformable_sim/core/base/parallel_for.h"

namespace deformable_sim::core {

void PreviousSolutions::reserve(int capacity, int size) {
  solutions_.setZero(size, capacity);
  right_hand_sides_.setZero(size, capacity);
  gram_.setZero(capacity, capacity);
  system_.setZero(capacity, capacity);
  partials_.setZero(capacity + 1, (size + kChunk - 1) / kChunk);
  dots_.setZero(capacity + 1);
  coefficients_.setZero(capacity);
  pending_rhs_.setZero(size);
  combination_.setZero(size);
  clear();
}

bool PreviousSolutions::guess(const Eigen::VectorXd& b,
                              const std::vector<std::uint8_t>& constrained, Eigen::VectorXd& x,
                              int threads) {
  const int m = count_;
  const int n = size();
  const int chunks = static_cast<int>(partials_.cols());
  // One pass: b_i . b for every stored b_i, b . b, and the copy of b kept for add().
  parallelFor(threads, 0, chunks, [&](int c) {
    const int begin = c * kChunk, length = std::min(kChunk, n - begin);
    const auto segment = b.segment(begin, length);
    partials_.col(c).head(m).noalias() =
        right_hand_sides_.block(begin, 0, length, m).transpose() * segment;
    partials_(m, c) = segment.squaredNorm();
    pending_rhs_.segment(begin, length) = segment;
  });
  auto dots = dots_.head(m + 1);
  dots.setZero();
  for (int c = 0; c < chunks; ++c) dots += partials_.col(c).head(m + 1);
  pending_ = true;
  if (m == 0) return false;
  // Normal equations of min |b - B alpha|: B^T B is singular or nearly so when the right-hand
  // sides repeat (a body at rest); a shift of 1e-14 of its largest entry keeps it definite and
  // damps only directions in which the stored right-hand sides span less than 1e-7 of the
  // largest of them, below the solver's tolerance.
  auto system = system_.topLeftCorner(m, m);
  system = gram_.topLeftCorner(m, m);
  const double largest = system.diagonal().maxCoeff();
  if (!(largest > 0.0)) return false;
  system.diagonal().array() += 1e-14 * largest;
  Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> cholesky(system);
  if (cholesky.info() != Eigen::Success) return false;
  auto coefficients = coefficients_.head(m);
  coefficients = dots.head(m);
  cholesky.solveInPlace(coefficients);
  if (!coefficients.allFinite()) return false;
  // The second pass: the combination, written to x on the free nodes.
  const int nodes = static_cast<int>(constrained.size());
  parallelFor(threads, 0, chunks, [&](int c) {
    const int begin = c * kChunk, length = std::min(kChunk, n - begin);
    combination_.segment(begin, length).noalias() =
        solutions_.block(begin, 0, length, m) * coefficients;
    const int last = std::min(nodes, (c + 1) * kChunk / 3);
    for (int i = c * kChunk / 3; i < last; ++i) {
      if (!constrained[i]) x.segment<3>(3 * i) = combination_.segment<3>(3 * i);
    }
  });
  return true;
}

void PreviousSolutions::add(const Eigen::VectorXd& x,
                            const std::vector<std::uint8_t>& constrained) {
  if (!pending_ || capacity() == 0) return;
  pending_ = false;
  const double squared_norm = dots_[count_];
  if (!(squared_norm > 0.0) || !std::isfinite(squared_norm) || !x.allFinite()) return;
  const int slot = next_;
  next_ = (next_ + 1) % capacity();
  const int old_count = count_;
  if (count_ < capacity()) ++count_;
  auto solution = solutions_.col(slot);
  solution = x;
  for (size_t i = 0; i < constrained.size(); ++i) {
    if (constrained[i]) solution.segment<3>(3 * i).setZero();
  }
  right_hand_sides_.col(slot) = pending_rhs_;
  // The new row and column of the Gram matrix: the dots of the guess (the slot's own entry was
  // the pair it replaces, if any) and b . b.
  for (int k = 0; k < old_count; ++k) {
    gram_(slot, k) = gram_(k, slot) = dots_[k];
  }
  gram_(slot, slot) = squared_norm;
}

}  // namespace deformable_sim::core
