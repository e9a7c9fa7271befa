#include "deformable_sim/core/solvers/rigid_mode_coarse_space.h"

#include <Eigen/Geometry>
#include <algorithm>

#include "deformable_sim/core/base/parallel_for.h"
#include "deformable_sim/core/base/rotation.h"
#include "deformable_sim/core/solvers/linear_solver.h"

namespace deformable_sim::core {

RigidModeCoarseSpace::RigidModeCoarseSpace(const BlockSparseMatrix& k) {
  // The finest aggregates (one ring) take the most work off the iterations, but their coarse
  // system grows faster than the mesh, and its scalar triangular solves cost several times a
  // product's four-wide multiply-adds per number: past kLargestFactorShare the iterations saved no
  // longer pay for the solves. Two rings keep the coarse system far smaller.
  build(k, 1);
  if (2.0 * coarse_.factorNonZeros() > kLargestFactorShare * 9.0 * k.numBlocks()) build(k, 2);
}

void RigidModeCoarseSpace::build(const BlockSparseMatrix& k, int rings) {
  rings_ = rings;
  aggregate(k, rings);
  listMembers();
  const std::vector<int> coarse_columns = buildCoarsePattern(k);
  buildScalarPattern(coarse_columns);
  const int n = k.numBlockRows();
  const int size = 6 * num_aggregates_;
  coarse_blocks_.resize(coarse_columns.size());
  coarse_rhs_.resize(size);
  modes_.resize(size);
  offset_.resize(n);
  centroid_.resize(num_aggregates_);
  centroid_count_.resize(num_aggregates_);
  largest_diagonal_.resize(num_aggregates_);
}

void RigidModeCoarseSpace::aggregate(const BlockSparseMatrix& k, int rings) {
  const int n = k.numBlockRows();
  const std::vector<int>& row_start = k.rowStart();
  const std::vector<int>& columns = k.columns();
  // Aggregation: a node whose rings of neighbours are untouched takes all of them ...
  num_aggregates_ = 0;
  aggregate_.assign(n, -1);
  std::vector<int> ring, seen(n, -1);
  for (int i = 0; i < n; ++i) {
    ring.assign(1, i);
    seen[i] = i;
    for (size_t first = 0, r = 0; r < static_cast<size_t>(rings); ++r) {
      const size_t last = ring.size();
      for (size_t q = first; q < last; ++q) {
        for (int s = row_start[ring[q]]; s < row_start[ring[q] + 1]; ++s) {
          if (seen[columns[s]] != i) {
            seen[columns[s]] = i;
            ring.push_back(columns[s]);
          }
        }
      }
      first = last;
    }
    if (std::any_of(ring.begin(), ring.end(), [&](int j) { return aggregate_[j] >= 0; })) continue;
    for (int j : ring) aggregate_[j] = num_aggregates_;
    ++num_aggregates_;
  }
  // ... and every node left over joins the aggregate of a neighbour (or starts one if isolated).
  for (int pass = 0; pass < 2; ++pass) {
    for (int i = 0; i < n; ++i) {
      if (aggregate_[i] >= 0) continue;
      for (int s = row_start[i]; s < row_start[i + 1] && aggregate_[i] < 0; ++s) {
        aggregate_[i] = aggregate_[columns[s]];
      }
      if (aggregate_[i] < 0 && pass == 1) aggregate_[i] = num_aggregates_++;
    }
  }
}

void RigidModeCoarseSpace::listMembers() {
  const int n = static_cast<int>(aggregate_.size());
  member_start_.assign(num_aggregates_ + 1, 0);
  for (int g : aggregate_) ++member_start_[g + 1];
  for (int g = 0; g < num_aggregates_; ++g) member_start_[g + 1] += member_start_[g];
  members_.resize(n);
  std::vector<int> next(member_start_.begin(), member_start_.end() - 1);
  for (int i = 0; i < n; ++i) members_[next[aggregate_[i]]++] = i;
}

std::vector<int> RigidModeCoarseSpace::buildCoarsePattern(const BlockSparseMatrix& k) {
  const int n = k.numBlockRows();
  const std::vector<int>& row_start = k.rowStart();
  const std::vector<int>& columns = k.columns();
  // Coarse pattern: blocks (agg(i), agg(j)) over the blocks (i, j) of the fine pattern.
  std::vector<std::vector<int>> neighbours(num_aggregates_);
  for (int i = 0; i < n; ++i) {
    for (int s = row_start[i]; s < row_start[i + 1]; ++s) {
      neighbours[aggregate_[i]].push_back(aggregate_[columns[s]]);
    }
  }
  coarse_row_start_.assign(1, 0);
  std::vector<int> coarse_columns;
  for (std::vector<int>& row : neighbours) {
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    coarse_columns.insert(coarse_columns.end(), row.begin(), row.end());
    coarse_row_start_.push_back(static_cast<int>(coarse_columns.size()));
  }
  auto coarseBlock = [&](int a, int b) {
    const auto begin = coarse_columns.begin() + coarse_row_start_[a];
    const auto end = coarse_columns.begin() + coarse_row_start_[a + 1];
    return static_cast<int>(std::lower_bound(begin, end, b) - coarse_columns.begin());
  };
  coarse_block_.resize(columns.size());
  for (int i = 0; i < n; ++i) {
    for (int s = row_start[i]; s < row_start[i + 1]; ++s) {
      coarse_block_[s] = coarseBlock(aggregate_[i], aggregate_[columns[s]]);
    }
  }
  return coarse_columns;
}

void RigidModeCoarseSpace::buildScalarPattern(const std::vector<int>& coarse_columns) {
  // The scalar coarse pattern, in a fill-reducing order computed once.
  const int size = 6 * num_aggregates_;
  std::vector<std::pair<int, int>> entries;
  entries.reserve(36 * coarse_columns.size());
  for (int a = 0; a < num_aggregates_; ++a) {
    for (int s = coarse_row_start_[a]; s < coarse_row_start_[a + 1]; ++s) {
      for (int e = 0; e < 36; ++e)
        entries.emplace_back(6 * a + e / 6, 6 * coarse_columns[s] + e % 6);
    }
  }
  coarse_value_ = coarse_.setPattern(size, entries);
  // A small coarse system is solved faster dense (its lower triangle, column-major).
  dense_ = 0.5 * size * (size + 1.0) <= kDenseSpeedup * (coarse_.factorNonZeros() + size);
  if (dense_) {
    for (size_t e = 0; e < entries.size(); ++e) {
      const auto [row, column] = entries[e];
      coarse_value_[e] = row >= column ? row + size * column : -1;
    }
    dense_coarse_.resize(size);
  }
  // Blocks whose every entry is its symmetric partner's are not computed at all.
  coarse_block_stored_.assign(coarse_columns.size(), 0);
  for (size_t b = 0; b < coarse_columns.size(); ++b) {
    for (int e = 0; e < 36; ++e) coarse_block_stored_[b] |= coarse_value_[36 * b + e] >= 0;
  }
}

void RigidModeCoarseSpace::refresh(const SystemMatrix& a, const ConstraintMask& constrained,
                                   const Eigen::VectorXd& positions) {
  updateOffsets(constrained, positions);
  // A_c = sum over blocks (i, j) of P_i^T A_ij P_j with P_i = [I, -[d_i]x]: the 3 x 6 map from
  // an aggregate's translation t and rotation w to node i's displacement t + w x d_i.
  // Every stored entry is written below: no zeroing. Aggregate by aggregate on the solver's
  // threads: the blocks of an aggregate's rows are summed by that aggregate alone, each over its
  // nodes' blocks in node order, as one loop over all nodes would: the same bits on any count.
  double* values = dense_ ? dense_coarse_.matrix().data() : coarse_.values();
  parallelFor(a.threads, 0, num_aggregates_,
              [&](int g) { assembleAggregateRows(g, a, constrained, values); });
  double largest_diagonal = 0.0;
  for (double largest : largest_diagonal_) largest_diagonal = std::max(largest_diagonal, largest);
  // Aggregates with constrained nodes can lose modes (all of them, or a rotation about the line
  // through their only free node): a tiny shift keeps A_c definite, and those modes carry no
  // residual, so it changes nothing else.
  const double shift = 1e-12 * largest_diagonal;
  if (dense_) {
    dense_coarse_.matrix().diagonal().array() += shift;
    dense_coarse_.factorize();
  } else {
    coarse_.factorize(shift);
  }
}

void RigidModeCoarseSpace::updateOffsets(const ConstraintMask& constrained,
                                         const Eigen::VectorXd& positions) {
  const int n = static_cast<int>(aggregate_.size());
  // Rotations about each aggregate's centroid of free nodes, at the current positions.
  std::fill(centroid_.begin(), centroid_.end(), Eigen::Vector3d::Zero());
  std::fill(centroid_count_.begin(), centroid_count_.end(), 0);
  for (int i = 0; i < n; ++i) {
    if (constrained[i]) continue;
    centroid_[aggregate_[i]] += positions.segment<3>(3 * i);
    ++centroid_count_[aggregate_[i]];
  }
  for (int g = 0; g < num_aggregates_; ++g) {
    if (centroid_count_[g] > 0) centroid_[g] /= centroid_count_[g];
  }
  for (int i = 0; i < n; ++i) offset_[i] = positions.segment<3>(3 * i) - centroid_[aggregate_[i]];
}

void RigidModeCoarseSpace::assembleAggregateRows(int g, const SystemMatrix& a,
                                                 const ConstraintMask& constrained,
                                                 double* values) {
  const BlockSparseMatrix& k = *a.stiffness;
  // Summed as whole 6 x 6 blocks (contiguous, vectorized), each then stored once.
  for (int b = coarse_row_start_[g]; b < coarse_row_start_[g + 1]; ++b) {
    coarse_blocks_[b].setZero();
  }
  double largest = 0.0;
  for (int m = member_start_[g]; m < member_start_[g + 1]; ++m) {
    const int i = members_[m];
    if (constrained[i]) continue;
    const Eigen::Matrix3d di = crossMatrix(offset_[i]);
    for (int s = k.rowStart()[i]; s < k.rowStart()[i + 1]; ++s) {
      const int j = k.columns()[s];
      if (constrained[j] || !coarse_block_stored_[coarse_block_[s]]) continue;
      Eigen::Matrix3d aij = a.stiffness_coefficient * k.blocks()[s];
      if (i == j && a.mass_coefficient != 0.0) {
        aij.diagonal().array() += a.mass_coefficient * (*a.nodal_mass)[i];
      }
      Eigen::Matrix<double, 3, 6> t;  // A_ij P_j
      t.leftCols<3>() = aij;
      t.rightCols<3>().noalias() = -aij * crossMatrix(offset_[j]);
      // P_i^T A_ij P_j; -[d]x^T = [d]x
      Eigen::Matrix<double, 6, 6>& block = coarse_blocks_[coarse_block_[s]];
      block.topRows<3>() += t;
      block.bottomRows<3>().noalias() += di * t;
      if (i == j) largest = std::max(largest, aij.diagonal().maxCoeff());
    }
  }
  for (int b = coarse_row_start_[g]; b < coarse_row_start_[g + 1]; ++b) {
    const int* slot = &coarse_value_[36 * b];
    for (int e = 0; e < 36; ++e) {
      if (slot[e] >= 0) values[slot[e]] = coarse_blocks_[b](e / 6, e % 6);
    }
  }
  largest_diagonal_[g] = largest;
}

void RigidModeCoarseSpace::restrictTo(int g, const ConstraintMask& constrained,
                                      const Eigen::VectorXd& r) {
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
  for (int k = member_start_[g]; k < member_start_[g + 1]; ++k) {
    const int i = members_[k];
    if (constrained[i]) continue;
    const Eigen::Vector3d ri = r.segment<3>(3 * i);
    force += ri;
    torque += offset_[i].cross(ri);
  }
  coarse_rhs_.segment<3>(6 * g) = force;
  coarse_rhs_.segment<3>(6 * g + 3) = torque;
}

void RigidModeCoarseSpace::solveCoarse() {
  if (dense_) {
    dense_coarse_.solve(coarse_rhs_, modes_);
  } else {
    coarse_.solve(coarse_rhs_, modes_);
  }
}

Eigen::Vector3d RigidModeCoarseSpace::correction(int i) const {
  const int g = 6 * aggregate_[i];
  return modes_.segment<3>(g) + modes_.segment<3>(g + 3).cross(offset_[i]);
}

void RigidModeCoarseSpace::addCorrection(const ConstraintMask& constrained,
                                         const Eigen::VectorXd& r, Eigen::VectorXd& z) {
  for (int g = 0; g < num_aggregates_; ++g) restrictTo(g, constrained, r);
  solveCoarse();
  for (size_t i = 0; i < aggregate_.size(); ++i) {
    if (!constrained[i]) z.segment<3>(3 * i) += correction(static_cast<int>(i));
  }
}

}  // namespace deformable_sim::core
