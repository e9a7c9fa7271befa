// The coarse level of the two-level preconditioner: nodes grouped into aggregates (a node and
// its mesh neighbours), each aggregate moving as a rigid body (3 translations, 3 small rotations
// about its centroid). Block-Jacobi smooths out the short wavelengths quickly but needs hundreds
// of iterations for the long ones (a beam bending as a whole); the coarse operator
// A_c = P^T A P over these modes takes those out in one solve, as in smoothed-aggregation
// multigrid (Vanek, Mandel, Brezina 1996) with its tentative prolongator.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "deformable_sim/core/solvers/block_sparse_matrix.h"
#include "deformable_sim/core/solvers/dense_cholesky.h"
#include "deformable_sim/core/solvers/preordered_ldlt.h"

namespace deformable_sim::core {

struct SystemMatrix;
using ConstraintMask = std::vector<std::uint8_t>;

class RigidModeCoarseSpace {
 public:
  /// Aggregates the nodes of the pattern of `k` (greedy: a node whose rings of neighbours are all
  /// free takes them; leftovers join a neighbouring aggregate) and builds the coarse pattern and
  /// its symbolic factorization. One ring where the coarse factor then holds (counted twice, for
  /// the two triangular solves) at most a fifth as many numbers as K, two otherwise. A small
  /// coarse system is kept dense (see kDenseSpeedup). Once per mesh.
  explicit RigidModeCoarseSpace(const BlockSparseMatrix& k);

  int numAggregates() const { return num_aggregates_; }
  int rings() const { return rings_; }   ///< of neighbours around an aggregate's first node
  bool dense() const { return dense_; }  ///< the coarse system kept as a dense matrix
  const std::vector<int>& aggregateOfNode() const { return aggregate_; }

  /// Recomputes A_c = P^T A P for the rigid modes of each aggregate at `positions`, over the free
  /// nodes, and factorizes it. Allocates nothing.
  void refresh(const SystemMatrix& a, const ConstraintMask& constrained,
               const Eigen::VectorXd& positions);

  /// The correction z += P A_c^-1 P^T r on the free nodes (r is zero on constrained nodes), in
  /// three parts that the conjugate gradient's threads share: the restriction of aggregate g
  /// (each aggregate sums its own nodes in node order), the coarse solve (one thread), and node
  /// i's part of the prolongation.
  void restrictTo(int g, const ConstraintMask& constrained, const Eigen::VectorXd& r);
  void solveCoarse();
  Eigen::Vector3d correction(int i) const;
  /// (P^T r) . z_c of the last restriction and coarse solve: r . (P z_c), the coarse
  /// correction's share of r . z. The same bits on every thread.
  double correctionDot() const { return coarse_rhs_.dot(modes_); }
  /// The three parts in turn, on the calling thread.
  void addCorrection(const ConstraintMask& constrained, const Eigen::VectorXd& r,
                     Eigen::VectorXd& z);

 private:
  static constexpr double kLargestFactorShare = 0.2;
  /// How many times as many numbers a dense triangular solve may take as the sparse factor's and
  /// still be the faster: its multiply-adds run four or eight wide from contiguous memory, the
  /// sparse one's one at a time through an index.
  static constexpr double kDenseSpeedup = 3.0;
  void build(const BlockSparseMatrix& k, int rings);
  /// Sets aggregate_ and num_aggregates_ for aggregates of `rings` rings of neighbours in k.
  void aggregate(const BlockSparseMatrix& k, int rings);
  /// Sets member_start_ and members_ from aggregate_.
  void listMembers();
  /// Sets coarse_row_start_ and coarse_block_; returns each coarse block's column aggregate.
  std::vector<int> buildCoarsePattern(const BlockSparseMatrix& k);
  /// The scalar pattern of A_c: its symbolic factorization or dense storage, coarse_value_ and
  /// coarse_block_stored_.
  void buildScalarPattern(const std::vector<int>& coarse_columns);
  /// Centroids of the aggregates' free nodes and each node's offset from its aggregate's.
  void updateOffsets(const ConstraintMask& constrained, const Eigen::VectorXd& positions);
  /// Sums the coarse blocks of aggregate g's rows and stores them into `values` (of the storage
  /// in use); largest_diagonal_[g] = the largest diagonal entry of its nodes' blocks.
  void assembleAggregateRows(int g, const SystemMatrix& a, const ConstraintMask& constrained,
                             double* values);

  int rings_ = 0;
  int num_aggregates_ = 0;
  std::vector<int> aggregate_;               ///< per node
  std::vector<int> member_start_, members_;  ///< the nodes of aggregate g, in node order
  std::vector<Eigen::Vector3d> offset_;      ///< per node: position minus its aggregate's centroid
  std::vector<Eigen::Vector3d> centroid_;
  std::vector<int> centroid_count_;
  std::vector<double> largest_diagonal_;  ///< per aggregate, of its nodes' diagonal blocks
  /// Per block of A (in the order of its storage): block (agg(i), agg(j)) of A_c.
  std::vector<int> coarse_block_;
  std::vector<int> coarse_row_start_;  ///< the coarse blocks of aggregate g's rows, contiguous
  std::vector<std::uint8_t> coarse_block_stored_;  ///< 0 where the symmetric partner is stored
  std::vector<Eigen::Matrix<double, 6, 6>> coarse_blocks_;  ///< per coarse block: its sum
  PreorderedLdlt coarse_;  ///< A_c and its factorization (sparse storage)
  bool dense_ = false;
  DenseCholesky dense_coarse_;     ///< A_c and its factorization (dense storage)
  std::vector<int> coarse_value_;  ///< per coarse block, 36 (row-major): index into the values of
                                   ///< the storage in use, or -1 where the symmetric partner is
  Eigen::VectorXd coarse_rhs_;     ///< P^T r by aggregate: force, torque
  Eigen::VectorXd modes_;          ///< the coarse solution by aggregate: translation, rotation
};

}  // namespace deformable_sim::core
