// The solutions of the last few systems of a sequence, kept with their right-hand sides, to start
// the next solve from the combination of the stored solutions whose right-hand sides best fit the
// new one (least squares: the projection onto previous solutions of Fischer, "Projection
// techniques for iterative solution of Ax = b with successive right-hand sides", 1998). Each pair
// was solved with a matrix of its own (the warped stiffness turns with the body), so the fit is a
// guess, not a solution; over a smooth motion it is a far better one than an extrapolation in
// time, and it costs no product with A: three passes over the stored vectors a solve.
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
  }

  /// Writes into x, on the nodes not constrained (3 entries a node), the combination of the
  /// stored solutions whose right-hand sides best fit b. False, x untouched, when none is stored
  /// or the fit fails.
  bool guess(const Eigen::VectorXd& b, const std::vector<std::uint8_t>& constrained,
             Eigen::VectorXd& x);

  /// Stores the pair (x, b), x taken as zero on constrained nodes, in place of the oldest pair
  /// when full. A zero b is not stored (it says nothing of the system).
  void add(const Eigen::VectorXd& x, const Eigen::VectorXd& b,
           const std::vector<std::uint8_t>& constrained);

 private:
  int count_ = 0;
  int next_ = 0;                      ///< the column the next pair goes to
  Eigen::MatrixXd solutions_;         ///< one pair a column (ring order)
  Eigen::MatrixXd right_hand_sides_;  ///< b of each stored solution
  Eigen::MatrixXd gram_;              ///< b_i . b_j
  Eigen::MatrixXd system_;            ///< the regularized Gram matrix, factorized in place
  Eigen::VectorXd fit_;               ///< b_i . b, then the coefficients of the guess
  Eigen::VectorXd combination_;
};

}  // namespace deformable_sim::core
