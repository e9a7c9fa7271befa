// Solvers for A x = b with A = c_m M + c_k K (M lumped mass, diagonal per node; K block-sparse)
// and some nodes constrained to prescribed values. Constrained rows and columns are projected out
// (the filtering of Baraff & Witkin 1998 / OpenTissue), so the pattern of K never changes when
// nodes are fixed or released.
#pragma once

#include <Eigen/Core>
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "deformable_sim/core/base/spin_barrier.h"
#include "deformable_sim/core/solvers/block_sparse_matrix.h"
#include "deformable_sim/core/solvers/preordered_ldlt.h"
#include "deformable_sim/core/solvers/previous_solutions.h"
#include "deformable_sim/core/solvers/rigid_mode_coarse_space.h"

namespace deformable_sim::core {

struct SolverSettings {
  enum class Method { kConjugateGradient, kDirect };
  /// Conjugate gradient preconditioners: block-Jacobi alone; block-Jacobi plus the coarse
  /// correction of RigidModeCoarseSpace (far fewer iterations on anything larger than a few
  /// hundred nodes); or a sparse LDL^T factorization of A, refactorized every
  /// coarse_refresh_interval solves (and when the constraints or coefficients change): a few
  /// iterations, each with two triangular solves (it allocates when it refactorizes).
  enum class Preconditioner { kBlockJacobi, kTwoLevel, kFactorization };
  Method method = Method::kConjugateGradient;
  Preconditioner preconditioner = Preconditioner::kTwoLevel;
  /// Conjugate gradient: relative residual ||r|| / max(||b_free||, reference floor); a step's
  /// floor is the impulse of its loads, h ||f_ext + M g|| on the free nodes (see
  /// ConjugateGradientSolver::solve).
  double tolerance = 1.0e-6;
  int max_iterations = 1000;  ///< conjugate gradient: iteration cap
  /// Two-level and factorization: the coarse operator or the factorization is rebuilt every
  /// this many solves (and whenever the mass or stiffness coefficient changes); in between the
  /// last one still preconditions well, since rotations change little from one step to the next.
  /// (What a rebuild costs, and what a longer interval costs in iterations: doc/performance.md.)
  int coarse_refresh_interval = 20;
  /// Threads for the element loops, products with A and CG's vector operations (1: none
  /// started). Every count sums in the same order: results are identical, bit for bit.
  int threads = 1;
  /// Conjugate gradient's initial guess for a step's velocity: the last velocity; the cubic
  /// through the last four (exact for motions smooth in time); or the combination of the last
  /// `previous_solutions` solutions whose right-hand sides best fit the step's (PreviousSolutions;
  /// the cubic until one is stored). On the default scene's pushed beam the projection starts CG
  /// about two orders of magnitude closer than the cubic and halves its iterations.
  enum class WarmStart { kLastVelocity, kExtrapolated, kProjected };
  WarmStart warm_start = WarmStart::kProjected;
  int previous_solutions = 32;  ///< pairs kept by the projected warm start
  /// With warping, a step is solved with the element rotations at its start (one linear solve,
  /// where a turn within the step costs no energy). When the rotations at its end would add more
  /// elastic energy than the step dissipates (fast turns, stiff bodies), it is solved again with
  /// the newer rotations, up to this many times: backward Euler with the exact corotational
  /// force, which never gains energy. 0: always the single solve. A step that gains nothing
  /// costs no more than one solve (its end rotations are the next step's start).
  int max_rotation_updates = 8;
};

struct SolveReport {
  int iterations = 0;  ///< CG iterations (0 for the direct solver)
  /// ||b - A x|| over the free rows / max(||b_free||, the solve's reference floor)
  double relative_residual = 0.0;
  bool converged = true;
  /// Of the solve's time, what refreshing the preconditioner took (zero when it was kept), s.
  double preconditioner_seconds = 0.0;
};

/// A node held on a plane only (contact sliding along an obstacle): A gains stiffness n n^T on
/// its diagonal block, a stiff spring along the plane's normal n that leaves the node free along
/// the plane.
struct PlaneHold {
  int node = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit
  double stiffness = 0.0;  ///< in A's units, set for each solve by the body
  double offset = 0.0;     ///< n . x the node is to end the step at, m
  double velocity = 0.0;   ///< n . v that takes it there in the step, m/s
};

/// The matrix of one solve: A = mass_coefficient M + stiffness_coefficient K (+ the springs of
/// nodes held on planes).
struct SystemMatrix {
  const BlockSparseMatrix* stiffness = nullptr;
  const std::vector<double>* nodal_mass = nullptr;  ///< kg per node (may be null if c_m == 0)
  double mass_coefficient = 0.0;
  double stiffness_coefficient = 1.0;
  /// Current node positions (3n), for the rigid modes of the two-level preconditioner.
  const Eigen::VectorXd* positions = nullptr;
  int threads = 1;  ///< for products and the conjugate gradient's vector operations
  const std::vector<PlaneHold>* planes = nullptr;  ///< none when null

  /// y = A x.
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  /// A's diagonal block of node i.
  Eigen::Matrix3d diagonalBlock(int i) const;
};

/// Which nodes are constrained (non-zero) for a solve.
using ConstraintMask = std::vector<std::uint8_t>;

class DirectSolver;

/// Preconditioned conjugate gradients. `x` comes in with the prescribed values on constrained
/// nodes and the initial guess elsewhere (a warm start), and leaves with the solution. Buffers and
/// the coarse space are set up on the first call; later calls of the same size allocate nothing.
/// Not to be called from inside an OpenMP parallel region: its iterations share their loops
/// among the threads of the region they run in (their own with settings.threads > 1).
class ConjugateGradientSolver {
 public:
  /// `in_sequence`: the system is the next of the sequence whose solutions the solver keeps
  /// (a body's steps): with the projected warm start, its initial guess on the free nodes comes
  /// from them, and its solution joins them. A change of the matrix's coefficients or of the
  /// constrained nodes starts a new sequence. `reference_floor`: the residual is measured
  /// against max(||b_free||, reference_floor). A body at rest under load has a right-hand side
  /// of rounding errors (its forces cancel); relative to that alone, CG would chase the
  /// rounding for dozens of iterations a step. `forcing`: CG may also stop once the residual is
  /// below this fraction of its first (an inexact Newton iteration needs no more; Eisenstat and
  /// Walker's forcing term).
  SolveReport solve(const SystemMatrix& a, const ConstraintMask& constrained,
                    const Eigen::VectorXd& b, const SolverSettings& settings, Eigen::VectorXd& x,
                    bool in_sequence = false, double reference_floor = 0.0, double forcing = 0.0);
  /// Forgets the stored solutions (the body was moved, or its material changed).
  void clearPreviousSolutions() { previous_.clear(); }

 private:
  void refreshPreconditioner(const SystemMatrix& a, const ConstraintMask& constrained,
                             const SolverSettings& settings);
  /// Sizes the vectors and partial sums for `num_nodes` nodes (`size` = 3 num_nodes), once.
  void resizeWorkspace(int num_nodes, Eigen::Index size);
  /// r_ = b - A x_c on the free rows (x_c: x on the constrained nodes, zero elsewhere; p_ holds
  /// it); returns |r_|.
  double setFreeRightHandSide(const SystemMatrix& a, const ConstraintMask& constrained,
                              const Eigen::VectorXd& b, const Eigen::VectorXd& x);
  /// The projected warm start's guess into x (the stored solutions' best fit to r_); false when
  /// it has none.
  bool guessFromPreviousSolutions(const SystemMatrix& a, const ConstraintMask& constrained,
                                  const SolverSettings& settings, Eigen::VectorXd& x);
  /// iterate() on a team of a.threads threads (one parallel region), or on this one.
  void iterateInTeam(const SystemMatrix& a, const ConstraintMask& constrained, double forcing,
                     const Eigen::VectorXd& b, const SolverSettings& settings, double reference,
                     int min_iterations, Eigen::VectorXd& x, SolveReport& report);
  /// The first residual r = b - A x and the iterations from it; run by each thread of a
  /// parallel region.
  void iterate(const SystemMatrix& a, const ConstraintMask& constrained, double forcing,
               const Eigen::VectorXd& b, const SolverSettings& settings, double reference,
               int min_iterations, Eigen::VectorXd& x, SolveReport& report);

  static constexpr int kChunkNodes = 32;  ///< nodes per partial sum of a dot product

  /// What the iterations' threads share besides the vectors (held by pointer: atomics do not
  /// move, the solver does).
  struct Team {
    SpinBarrier barrier;
    std::atomic<int> next_chunk{0};  ///< of block-Jacobi's loop, whose chunks threads claim
  };

  std::vector<Eigen::Matrix3d> inverse_diagonal_;
  Eigen::VectorXd r_, z_, p_, q_;
  /// Per chunk of nodes: p . q, |r|^2 and r . z. Three buffers, so that no thread overwrites
  /// one before every thread has read it (a barrier always separates the two).
  std::vector<double> pq_partials_, rr_partials_, rz_partials_;
  std::unique_ptr<RigidModeCoarseSpace> coarse_;
  std::unique_ptr<DirectSolver> factorization_;  ///< Preconditioner::kFactorization
  std::unique_ptr<Team> team_ = std::make_unique<Team>();
  PreviousSolutions previous_;  ///< WarmStart::kProjected
  ConstraintMask previous_constraints_;
  double previous_mass_coefficient_ = 0.0, previous_stiffness_coefficient_ = 0.0;
  ConstraintMask factorized_constraints_;
  int solves_since_coarse_refresh_ = 0;
  double coarse_mass_coefficient_ = 0.0, coarse_stiffness_coefficient_ = 0.0;
};

/// Sparse LDL^T factorization (Eigen's SimplicialLDLT in a fill-reducing order). The scalar
/// pattern and its ordering are computed on the first solve; later solves refill values and
/// refactorize only when told the matrix or the constraint set changed, allocating nothing up to
/// 5 461 nodes (see PreorderedLdlt).
class DirectSolver {
 public:
  SolveReport solve(const SystemMatrix& a, const ConstraintMask& constrained,
                    const Eigen::VectorXd& b, bool matrix_changed, Eigen::VectorXd& x);

  /// Factorizes A with the constrained rows and columns made identity ones; false if it failed.
  bool factorize(const SystemMatrix& a, const ConstraintMask& constrained);
  /// z = A^-1 r with the last factorization (zero on constrained rows where r is).
  void applyInverse(const Eigen::VectorXd& r, Eigen::VectorXd& z);

 private:
  void buildPattern(const BlockSparseMatrix& k);

  PreorderedLdlt factorization_;
  std::vector<int> value_of_block_entry_;  ///< 9 per block: index into its values, or -1
  Eigen::VectorXd rhs_, product_;
  bool analysed_ = false;
  bool factorized_ = false;
};

}  // namespace deformable_sim::core
