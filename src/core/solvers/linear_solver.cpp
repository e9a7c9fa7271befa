#include "deformable_sim/core/solvers/linear_solver.h"

#include <chrono>

#if defined(_OPENMP)
#include <omp.h>
#endif

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "deformable_sim/core/base/parallel_for.h"

namespace deformable_sim::core {

namespace {

// The calling thread's team: its size and this thread's place in it (1 and 0 outside a parallel
// region, or in a build without OpenMP).
int teamSize() {
#if defined(_OPENMP)
  return omp_get_num_threads();
#else
  return 1;
#endif
}

int threadInTeam() {
#if defined(_OPENMP)
  return omp_get_thread_num();
#else
  return 0;
#endif
}

void zeroConstrained(const ConstraintMask& constrained, Eigen::VectorXd& v) {
  for (size_t i = 0; i < constrained.size(); ++i) {
    if (constrained[i]) v.segment<3>(3 * i).setZero();
  }
}

// v = x on constrained nodes, 0 elsewhere.
void keepConstrained(const ConstraintMask& constrained, const Eigen::VectorXd& x,
                     Eigen::VectorXd& v) {
  for (size_t i = 0; i < constrained.size(); ++i) {
    v.segment<3>(3 * i) =
        constrained[i] ? Eigen::Vector3d(x.segment<3>(3 * i)) : Eigen::Vector3d::Zero();
  }
}

// Whether x is non-zero on some constrained node: fixed nodes that move (a grasp), not a clamp.
bool prescribesMotion(const ConstraintMask& constrained, const Eigen::VectorXd& x) {
  for (size_t i = 0; i < constrained.size(); ++i) {
    if (constrained[i] && !x.segment<3>(3 * i).isZero(0.0)) return true;
  }
  return false;
}

}  // namespace

namespace {

// Rows begin .. end - 1 of y = A x = c_k K x + c_m M x.
void multiplyRows(const SystemMatrix& a, int begin, int end, const Eigen::VectorXd& x,
                  Eigen::VectorXd& y) {
  a.stiffness->multiplyRows(begin, end, x.data(), y.data(), a.stiffness_coefficient,
                            a.mass_coefficient != 0.0 ? a.nodal_mass->data() : nullptr,
                            a.mass_coefficient);
  if (!a.planes) return;
  for (const PlaneHold& p : *a.planes) {
    if (p.node < begin || p.node >= end) continue;
    y.segment<3>(3 * p.node) += p.stiffness * p.normal.dot(x.segment<3>(3 * p.node)) * p.normal;
  }
}

}  // namespace

void SystemMatrix::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  constexpr int kRows = 32;  // rows a thread takes at a time
  const int num_rows = stiffness->numBlockRows();
  parallelFor(threads, 0, (num_rows + kRows - 1) / kRows, [&](int c) {
    multiplyRows(*this, c * kRows, std::min(num_rows, (c + 1) * kRows), x, y);
  });
}

Eigen::Matrix3d SystemMatrix::diagonalBlock(int i) const {
  Eigen::Matrix3d d = stiffness_coefficient * stiffness->blocks()[stiffness->diagonalIndex(i)];
  if (mass_coefficient != 0.0) d.diagonal().array() += mass_coefficient * (*nodal_mass)[i];
  if (planes) {
    for (const PlaneHold& p : *planes) {
      if (p.node == i) d += p.stiffness * p.normal * p.normal.transpose();
    }
  }
  return d;
}

void ConjugateGradientSolver::refreshPreconditioner(const SystemMatrix& a,
                                                    const ConstraintMask& constrained,
                                                    const SolverSettings& settings) {
  const int num_nodes = a.stiffness->numBlockRows();
  parallelFor(a.threads, 0, num_nodes, [&](int i) {
    if (constrained[i]) {
      inverse_diagonal_[i].setZero();  // keeps every search direction zero on constrained nodes
      return;
    }
    inverse_diagonal_[i] = a.diagonalBlock(i).inverse();
  });
  if (settings.preconditioner == SolverSettings::Preconditioner::kFactorization) {
    const bool fresh = !factorization_;
    if (fresh) factorization_ = std::make_unique<DirectSolver>();
    if (fresh || ++solves_since_coarse_refresh_ >= settings.coarse_refresh_interval ||
        a.mass_coefficient != coarse_mass_coefficient_ ||
        a.stiffness_coefficient != coarse_stiffness_coefficient_ ||
        constrained != factorized_constraints_) {
      // A failed factorization (A not definite) leaves block-Jacobi to work alone.
      if (!factorization_->factorize(a, constrained)) factorization_.reset();
      factorized_constraints_ = constrained;
      solves_since_coarse_refresh_ = 0;
      coarse_mass_coefficient_ = a.mass_coefficient;
      coarse_stiffness_coefficient_ = a.stiffness_coefficient;
    }
    return;
  }
  // Without positions (no rigid modes to build) block-Jacobi works alone.
  if (settings.preconditioner != SolverSettings::Preconditioner::kTwoLevel || !a.positions) return;
  const bool fresh = !coarse_;
  if (fresh) coarse_ = std::make_unique<RigidModeCoarseSpace>(*a.stiffness);
  if (fresh || ++solves_since_coarse_refresh_ >= settings.coarse_refresh_interval ||
      a.mass_coefficient != coarse_mass_coefficient_ ||
      a.stiffness_coefficient != coarse_stiffness_coefficient_) {
    coarse_->refresh(a, constrained, *a.positions);
    solves_since_coarse_refresh_ = 0;
    coarse_mass_coefficient_ = a.mass_coefficient;
    coarse_stiffness_coefficient_ = a.stiffness_coefficient;
  }
}

namespace {

// A loop shared by the threads of the enclosing parallel region in contiguous, near-equal parts
// (OpenMP's static schedule), ending at the barrier; run whole by the calling thread outside one.
template <typename Function>
void shareLoop(SpinBarrier& barrier, int begin, int end, Function&& body) {
  const int threads = teamSize(), thread = threadInTeam();
  const int share = (end - begin) / threads, extra = (end - begin) % threads;
  const int first = begin + thread * share + std::min(thread, extra);
  const int last = first + share + (thread < extra ? 1 : 0);
  for (int i = first; i < last; ++i) body(i);
  barrier.arriveAndWait();
}

// The sum of per-chunk partial sums in chunk order: every thread gets the same bits.
double total(const std::vector<double>& partials) {
  double sum = 0.0;
  for (double partial : partials) sum += partial;
  return sum;
}

}  // namespace

// A documented numeric kernel, kept in one piece: the preconditioned conjugate gradient of one
// parallel region. Every thread of the team runs all of it; its steps are lambdas over the
// team's chunks that share the thread's scalars, the barrier and the partial sums, so that the
// threads take the same branches and meet at the same barriers in the same order.
void ConjugateGradientSolver::iterate(const SystemMatrix& a, const ConstraintMask& constrained,
                                      double forcing, const Eigen::VectorXd& b,
                                      const SolverSettings& settings, double reference,
                                      int min_iterations, Eigen::VectorXd& x, SolveReport& report) {
  // Run by every thread of the team with its own copy of the scalars: each sums the same
  // partials in the same order, so all take the same branches and meet at the same barriers.
  const int num_nodes = a.stiffness->numBlockRows();
  const int num_chunks = static_cast<int>(pq_partials_.size());
  const bool first_thread = threadInTeam() == 0;
  SpinBarrier& barrier = team_->barrier;
  auto chunkEnd = [&](int c) { return std::min(num_nodes, (c + 1) * kChunkNodes); };
  int iterations = 0;
  // Chunk c of a vector: its nodes' entries, one contiguous (vectorized) segment.
  auto chunk = [&](Eigen::VectorXd& v, int c) {
    const int begin = 3 * kChunkNodes * c;
    return v.segment(begin, 3 * chunkEnd(c) - begin);
  };
  // Block-Jacobi on chunk c, and its part of r . z.
  auto blockJacobi = [&](int c) {
    for (int i = c * kChunkNodes; i < chunkEnd(c); ++i) {
      z_.segment<3>(3 * i).noalias() = inverse_diagonal_[i] * r_.segment<3>(3 * i);
    }
    rz_partials_[c] = chunk(r_, c).dot(chunk(z_, c));
  };
  // z = B r: block-Jacobi plus the coarse correction (additive: the two parts see the same r, so
  // B stays symmetric positive definite and costs no extra product with A), and r . z: with the
  // coarse space, block-Jacobi's part of it (the correction is added with the update of p).
  auto precondition = [&]() {
    if (factorization_) {
      if (first_thread) factorization_->applyInverse(r_, z_);
      barrier.arriveAndWait();
      shareLoop(barrier, 0, num_chunks,
                [&](int c) { rz_partials_[c] = chunk(r_, c).dot(chunk(z_, c)); });
    } else if (coarse_) {
      shareLoop(barrier, 0, coarse_->numAggregates(),
                [&](int g) { coarse_->restrictTo(g, constrained, r_); });
      // One thread solves the coarse system while the others start on block-Jacobi's chunks.
      if (first_thread) coarse_->solveCoarse();
      std::atomic<int>& next_chunk = team_->next_chunk;
      for (int c = next_chunk++; c < num_chunks; c = next_chunk++) blockJacobi(c);
      barrier.arriveAndWait();
      if (first_thread) next_chunk = 0;  // for the next use: barriers come first
    } else {
      shareLoop(barrier, 0, num_chunks, blockJacobi);
    }
  };
  // z + the coarse correction, on chunk c.
  auto addCorrection = [&](int c) {
    if (!coarse_) return;
    for (int i = c * kChunkNodes; i < chunkEnd(c); ++i) {
      if (!constrained[i]) z_.segment<3>(3 * i) += coarse_->correction(i);
    }
  };

  // The first residual r = b - A x (zero on constrained rows), its preconditioned z, p = z.
  shareLoop(barrier, 0, num_chunks, [&](int c) {
    multiplyRows(a, c * kChunkNodes, chunkEnd(c), x, q_);
    for (int i = c * kChunkNodes; i < chunkEnd(c); ++i) {
      r_.segment<3>(3 * i) = constrained[i]
                                 ? Eigen::Vector3d::Zero()
                                 : Eigen::Vector3d(b.segment<3>(3 * i) - q_.segment<3>(3 * i));
    }
    rr_partials_[c] = chunk(r_, c).squaredNorm();
  });
  precondition();
  shareLoop(barrier, 0, num_chunks, [&](int c) {
    addCorrection(c);
    chunk(p_, c) = chunk(z_, c);
    rz_partials_[c] = chunk(r_, c).dot(chunk(z_, c));
  });
  double rz = total(rz_partials_);
  double residual = std::sqrt(total(rr_partials_)) / reference;
  const double tolerance = std::max(settings.tolerance, forcing * residual);
  while ((residual > tolerance || iterations < min_iterations) &&
         iterations < settings.max_iterations) {
    // q = A p (zero on constrained rows), and p . q.
    shareLoop(barrier, 0, num_chunks, [&](int c) {
      multiplyRows(a, c * kChunkNodes, chunkEnd(c), p_, q_);
      for (int i = c * kChunkNodes; i < chunkEnd(c); ++i) {
        if (constrained[i]) q_.segment<3>(3 * i).setZero();
      }
      pq_partials_[c] = chunk(p_, c).dot(chunk(q_, c));
    });
    const double pq = total(pq_partials_);
    if (!(pq > 0.0)) break;  // not positive definite along p (or NaN): stop, report below
    const double alpha = rz / pq;
    // x += alpha p, r -= alpha q, and |r|^2.
    shareLoop(barrier, 0, num_chunks, [&](int c) {
      chunk(x, c) += alpha * chunk(p_, c);
      chunk(r_, c) -= alpha * chunk(q_, c);
      rr_partials_[c] = chunk(r_, c).squaredNorm();
    });
    precondition();
    // With the coarse correction z = z_J + P z_c, r . z = r . z_J + (P^T r) . z_c: the coarse
    // part is known as soon as z_c is, so the prolongation and the update of p take one pass.
    const double rz_next = total(rz_partials_) + (coarse_ ? coarse_->correctionDot() : 0.0);
    const double beta = rz_next / rz;
    shareLoop(barrier, 0, num_chunks, [&](int c) {
      addCorrection(c);
      chunk(p_, c) = chunk(z_, c) + beta * chunk(p_, c);
    });
    rz = rz_next;
    residual = std::sqrt(total(rr_partials_)) / reference;
    ++iterations;
  }
  if (first_thread) {
    report.iterations = iterations;
    report.relative_residual = residual;
    report.converged = residual <= tolerance;
  }
}

SolveReport ConjugateGradientSolver::solve(const SystemMatrix& a, const ConstraintMask& constrained,
                                           const Eigen::VectorXd& b, const SolverSettings& settings,
                                           Eigen::VectorXd& x, bool in_sequence,
                                           double reference_floor, double forcing) {
  resizeWorkspace(a.stiffness->numBlockRows(), b.size());
  if (settings.preconditioner != SolverSettings::Preconditioner::kTwoLevel) coarse_.reset();
  if (settings.preconditioner != SolverSettings::Preconditioner::kFactorization) {
    factorization_.reset();
  }
  const auto refresh_start = std::chrono::steady_clock::now();
  refreshPreconditioner(a, constrained, settings);
  SolveReport report;
  report.preconditioner_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - refresh_start).count();
  const double free_norm = setFreeRightHandSide(a, constrained, b, x);
  if (!std::isfinite(free_norm)) {
    // A non-finite right-hand side: nothing to solve; say so rather than return a "solution".
    report.converged = false;
    report.relative_residual = free_norm;
    return report;
  }
  if (!(free_norm > 0.0)) {
    // Free rows have a zero right-hand side: the solution is zero there.
    x = p_;
    return report;
  }
  const double reference =
      std::isfinite(reference_floor) ? std::max(free_norm, reference_floor) : free_norm;
  // A projected guess takes at least one iteration even when it meets the tolerance already:
  // in a steady motion it repeats the last solution's error, which would otherwise pass from
  // step to step unchecked and add up (a free fall then drifts from implicit Euler); one
  // iteration with the coarse space's rigid modes takes the common part of it out.
  const bool project = in_sequence &&
                       settings.warm_start == SolverSettings::WarmStart::kProjected &&
                       settings.previous_solutions > 0;
  const bool projected = project && guessFromPreviousSolutions(a, constrained, settings, x);
  iterateInTeam(a, constrained, forcing, b, settings, reference, projected ? 1 : 0, x, report);
  if (project && report.converged) previous_.add(x, constrained);
  return report;
}

void ConjugateGradientSolver::resizeWorkspace(int num_nodes, Eigen::Index size) {
  if (r_.size() == size) return;
  r_.resize(size);
  z_.resize(size);
  p_.resize(size);
  q_.resize(size);
  inverse_diagonal_.resize(num_nodes);
  const int num_chunks = (num_nodes + kChunkNodes - 1) / kChunkNodes;
  pq_partials_.resize(num_chunks);
  rr_partials_.resize(num_chunks);
  rz_partials_.resize(num_chunks);
}

double ConjugateGradientSolver::setFreeRightHandSide(const SystemMatrix& a,
                                                     const ConstraintMask& constrained,
                                                     const Eigen::VectorXd& b,
                                                     const Eigen::VectorXd& x) {
  // Reference norm: the right-hand side of the free rows once the prescribed values are moved
  // over, i.e. the residual of x = 0 on the free nodes.
  keepConstrained(constrained, x, p_);
  if (prescribesMotion(constrained, x)) {
    a.multiply(p_, q_);
    r_ = b - q_;
  } else {
    r_ = b;  // A 0 = 0: no product needed
  }
  zeroConstrained(constrained, r_);
  return r_.norm();
}

bool ConjugateGradientSolver::guessFromPreviousSolutions(const SystemMatrix& a,
                                                         const ConstraintMask& constrained,
                                                         const SolverSettings& settings,
                                                         Eigen::VectorXd& x) {
  if (previous_.capacity() != settings.previous_solutions || previous_.size() != r_.size()) {
    previous_.reserve(settings.previous_solutions, static_cast<int>(r_.size()));
  }
  // The stored pairs solved another system: start afresh.
  if (a.mass_coefficient != previous_mass_coefficient_ ||
      a.stiffness_coefficient != previous_stiffness_coefficient_ ||
      constrained != previous_constraints_) {
    previous_.clear();
    previous_mass_coefficient_ = a.mass_coefficient;
    previous_stiffness_coefficient_ = a.stiffness_coefficient;
    previous_constraints_ = constrained;
  }
  // r_ is b - A x_c on the free nodes: what the stored solutions solved, and this one will.
  return previous_.guess(r_, constrained, x, a.threads);
}

void ConjugateGradientSolver::iterateInTeam(const SystemMatrix& a,
                                            const ConstraintMask& constrained, double forcing,
                                            const Eigen::VectorXd& b,
                                            const SolverSettings& settings, double reference,
                                            int min_iterations, Eigen::VectorXd& x,
                                            SolveReport& report) {
  // One parallel region for all the iterations: starting one costs more than a short loop.
  team_->next_chunk = 0;
  if (a.threads > 1) {
#pragma omp parallel num_threads(a.threads)
    {
      // The team OpenMP gave (it may be smaller than asked) is the one the barrier waits for.
#pragma omp single
      team_->barrier.reset(teamSize());
      iterate(a, constrained, forcing, b, settings, reference, min_iterations, x, report);
    }
  } else {
    team_->barrier.reset(1);
    iterate(a, constrained, forcing, b, settings, reference, min_iterations, x, report);
  }
}

void DirectSolver::buildPattern(const BlockSparseMatrix& k) {
  const int n = k.numBlockRows();
  std::vector<std::pair<int, int>> entries;
  entries.reserve(9 * k.numBlocks());
  for (int i = 0; i < n; ++i) {
    for (int s = k.rowStart()[i]; s < k.rowStart()[i + 1]; ++s) {
      for (int e = 0; e < 9; ++e) entries.emplace_back(3 * i + e / 3, 3 * k.columns()[s] + e % 3);
    }
  }
  value_of_block_entry_ = factorization_.setPattern(3 * n, entries);
  rhs_.resize(3 * n);
  product_.resize(3 * n);
  analysed_ = true;
}

bool DirectSolver::factorize(const SystemMatrix& a, const ConstraintMask& constrained) {
  const BlockSparseMatrix& k = *a.stiffness;
  if (!analysed_) buildPattern(k);
  double* values = factorization_.values();
  for (int i = 0; i < k.numBlockRows(); ++i) {
    for (int s = k.rowStart()[i]; s < k.rowStart()[i + 1]; ++s) {
      const int j = k.columns()[s];
      const bool projected = constrained[i] || constrained[j];
      Eigen::Matrix3d block = i == j ? a.diagonalBlock(i) : a.stiffness_coefficient * k.blocks()[s];
      // Constrained rows and columns become identity rows: x_c = prescribed value.
      if (projected) {
        block.setZero();
        if (i == j) block.setIdentity();
      }
      for (int e = 0; e < 9; ++e) {
        const int v = value_of_block_entry_[9 * s + e];
        if (v >= 0) values[v] = block(e / 3, e % 3);  // the other triangle holds the rest
      }
    }
  }
  factorized_ = factorization_.factorize();
  return factorized_;
}

void DirectSolver::applyInverse(const Eigen::VectorXd& r, Eigen::VectorXd& z) {
  factorization_.solve(r, z);
}

SolveReport DirectSolver::solve(const SystemMatrix& a, const ConstraintMask& constrained,
                                const Eigen::VectorXd& b, bool matrix_changed, Eigen::VectorXd& x) {
  const BlockSparseMatrix& k = *a.stiffness;
  if (matrix_changed || !analysed_) factorize(a, constrained);
  SolveReport report;
  if (!factorized_) {
    report.converged = false;
    report.relative_residual = std::nan("");
    return report;
  }
  // Move the prescribed values to the right-hand side of the free rows.
  keepConstrained(constrained, x, rhs_);
  a.multiply(rhs_, product_);
  const Eigen::VectorXd& prescribed = x;
  for (int i = 0; i < k.numBlockRows(); ++i) {
    rhs_.segment<3>(3 * i) =
        constrained[i] ? Eigen::Vector3d(prescribed.segment<3>(3 * i))
                       : Eigen::Vector3d(b.segment<3>(3 * i) - product_.segment<3>(3 * i));
  }
  const double reference = [&] {
    double sum = 0.0;
    for (int i = 0; i < k.numBlockRows(); ++i) {
      if (!constrained[i]) sum += rhs_.segment<3>(3 * i).squaredNorm();
    }
    return std::sqrt(sum);
  }();
  factorization_.solve(rhs_, x);
  a.multiply(x, product_);
  product_ = b - product_;
  zeroConstrained(constrained, product_);
  report.relative_residual = reference > 0.0 ? product_.norm() / reference : 0.0;
  return report;
}

}  // namespace deformable_sim::core
