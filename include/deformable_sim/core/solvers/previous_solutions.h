// The solutions of the last few systems of a sequence, kept with their right-hand sides, to start
// the next solve from the combination of the stored solutions whose right-hand sides best fit the
// new one (least squares: the projection onto previous solutions of Fischer, "Projection
// techniques for iterative solution of Ax = b with successive right-hand sides", 1998). Each pair
// was solved with a matrix of its own (the warped stiffness turns with the body), so the fit is a
// guess, not a solution; over a smooth motion it is a far better one than an extrapolation in
// time, and it costs no product with A: two passes over the stored vectors a solve.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace deformable_sim::core {

class PreviousSolutions {
 public:
  /// Room for `capacity` pairs of vectors of `size` entries, none stored. Allocates; once sized,
  /// nothing else does.
  void reserve(int capacity, int size);
  int capacity() const { return static_cast<int>(solutions_.cols()); }
  int size() const { return static_cast<int>(solutions_.rows()); }
  int count() const { return count_; }
  /// Forgets every pair; the next ones are stored as in a new object (same sums, same bits).
  void clear() {
    count_ = 0;
    next_ = 0;
    pending_ = false;
  }

  /// Writes into x, on the nodes not constrained (3 entries a node), the combination of the
  /// stored solutions whose right-hand sides best fit b, and remembers b for add(). False, x
  /// untouched, when none is stored or the fit fails. Sums run over fixed chunks of entries on
  /// `threads` threads: the same bits on any count.
  bool guess(const Eigen::VectorXd& b, const std::vector<std::uint8_t>& constrained,
             Eigen::VectorXd& x, int threads = 1);

  /// Stores x, taken as zero on constrained nodes, as the solution of the last guess's b, in
  /// place of the oldest pair when full. Nothing is stored without a guess since the last add,
  /// or for a zero b (it says nothing of the system).
  void add(const Eigen::VectorXd& x, const std::vector<std::uint8_t>& constrained);

 private:
  static constexpr int kChunk = 96;  ///< entries a partial sum covers (32 nodes)

  int count_ = 0;
  int next_ = 0;                      ///< the column the next pair goes to
  Eigen::MatrixXd solutions_;         ///< one pair a column (ring order)
  Eigen::MatrixXd right_hand_sides_;  ///< b of each stored solution
  Eigen::MatrixXd gram_;              ///< b_i . b_j
  Eigen::MatrixXd system_;            ///< the regularized Gram matrix, factorized in place
  Eigen::MatrixXd partials_;          ///< per chunk: b_i . b over its entries, then b . b
  Eigen::VectorXd dots_;              ///< b_i . b (i < count_), then b . b, of the pending b
  Eigen::VectorXd coefficients_;
  Eigen::VectorXd combination_;
  Eigen::VectorXd pending_rhs_;  ///< b of the last guess
  bool pending_ = false;
};

}  // namespace deformable_sim::core
