// The linear solvers on a real warped system: products agree with the dense matrix, both
// conjugate gradient preconditioners reach the direct solution, the two-level one in far fewer
// iterations, its coarse correction is exact on the body's rigid motions (with the coarse system
// kept dense or sparse), and a stale coarse operator still preconditions after constraints
// change. The dense Cholesky solve of small coarse systems agrees with Eigen's.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <atomic>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include "deformable_sim/core/base/spin_barrier.h"
#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/elements/corotational_elasticity.h"
#include "deformable_sim/core/solvers/dense_cholesky.h"
#include "deformable_sim/core/solvers/linear_solver.h"
#include "deformable_sim/core/solvers/rigid_mode_coarse_space.h"

namespace dc = deformable_sim::core;

namespace {

using Preconditioner = dc::SolverSettings::Preconditioner;

// A bent, twisted beam: the warped stiffness of a real deformed state.
struct WarpedSystem {
  const dc::LinearElasticMaterial material{1e6, 0.35, 1000.0};
  dc::Mesh mesh;
  dc::CorotationalElasticity elasticity{mesh, material};
  std::vector<double> masses = dc::lumpedMasses(mesh, material.density);
  Eigen::VectorXd x;
  dc::ConstraintMask constrained;
  Eigen::VectorXd b;

  explicit WarpedSystem(const Eigen::Vector3i& cells = {32, 4, 4})
      : mesh(dc::makeBoxMesh({0, -0.05, -0.05}, {1.2, 0.05, 0.05}, cells)),
        x(3 * mesh.numNodes()),
        constrained(mesh.numNodes(), 0) {
    for (int i = 0; i < mesh.numNodes(); ++i) {
      const Eigen::Vector3d& p = mesh.positions[i];
      const Eigen::AngleAxisd twist(0.8 * p.x(), Eigen::Vector3d::UnitX());
      x.segment<3>(3 * i) = twist * p + Eigen::Vector3d(0, 0.1 * p.x() * p.x(), -0.2 * p.x());
      constrained[i] = p.x() < 1e-9;
    }
    elasticity.update(x, true);
    b = Eigen::VectorXd::LinSpaced(x.size(), -1.0, 2.0).array().sin();
  }

  dc::SystemMatrix matrix() const {
    dc::SystemMatrix a;
    a.stiffness = &elasticity.stiffness();
    a.nodal_mass = &masses;
    a.mass_coefficient = 1.0;
    a.stiffness_coefficient = 1e-4;  // h = 0.01 s
    a.positions = &x;
    return a;
  }

  Eigen::VectorXd direct() const {
    dc::DirectSolver solver;
    Eigen::VectorXd solution = Eigen::VectorXd::Zero(b.size());
    solver.solve(matrix(), constrained, b, true, solution);
    return solution;
  }
};

dc::SolverSettings cg(Preconditioner preconditioner, double tolerance = 1e-10) {
  dc::SolverSettings settings;
  settings.preconditioner = preconditioner;
  settings.tolerance = tolerance;
  settings.max_iterations = 5000;
  return settings;
}

}  // namespace

// The products' inner loop (four-wide multiply-adds where the CPU has them) against the dense
// matrix: whole products, any range of rows, and A = c_m M + c_k K on one and two threads.
TEST(LinearSolver, ProductsAgreeWithTheDenseMatrix) {
  const WarpedSystem system;
  const dc::BlockSparseMatrix& k = system.elasticity.stiffness();
  const Eigen::MatrixXd dense = k.toDense();
  const Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(system.b.size(), -3.0, 1.0).array().cos();
  const Eigen::VectorXd expected = dense * v;
  Eigen::VectorXd y(v.size());
  k.multiply(v, y);
  EXPECT_LE((y - expected).norm(), 1e-13 * expected.norm());

  Eigen::VectorXd rows = Eigen::VectorXd::Constant(v.size(), 7.0);
  k.multiplyRows(5, 17, v.data(), rows.data());
  EXPECT_EQ(rows.segment(15, 36), y.segment(15, 36));  // the same sums, bit for bit
  EXPECT_EQ(rows.head(15), Eigen::VectorXd::Constant(15, 7.0));
  EXPECT_EQ(rows.tail(v.size() - 51), Eigen::VectorXd::Constant(v.size() - 51, 7.0));

  dc::SystemMatrix a = system.matrix();
  Eigen::MatrixXd a_dense = a.stiffness_coefficient * dense;
  for (int i = 0; i < system.mesh.numNodes(); ++i) {
    a_dense.diagonal().segment<3>(3 * i).array() += a.mass_coefficient * system.masses[i];
  }
  Eigen::VectorXd one_thread(v.size()), two_threads(v.size());
  a.multiply(v, one_thread);
  a.threads = 2;
  a.multiply(v, two_threads);
  EXPECT_LE((one_thread - a_dense * v).norm(), 1e-13 * (a_dense * v).norm());
  EXPECT_EQ(one_thread, two_threads);
}

TEST(LinearSolver, BothPreconditionersReachTheDirectSolutionTheTwoLevelOneFarSooner) {
  WarpedSystem system;
  const Eigen::VectorXd expected = system.direct();
  int iterations[2];
  for (Preconditioner p : {Preconditioner::kBlockJacobi, Preconditioner::kTwoLevel}) {
    dc::ConjugateGradientSolver solver;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(system.b.size());
    const dc::SolveReport report =
        solver.solve(system.matrix(), system.constrained, system.b, cg(p), x);
    EXPECT_TRUE(report.converged);
    EXPECT_LE(report.relative_residual, 1e-10);
    EXPECT_NEAR((x - expected).norm() / expected.norm(), 0.0, 1e-8);
    iterations[static_cast<int>(p)] = report.iterations;
  }
  RecordProperty("block_jacobi_iterations", iterations[0]);
  RecordProperty("two_level_iterations", iterations[1]);
  EXPECT_LT(2 * iterations[1], iterations[0])
      << "block-Jacobi " << iterations[0] << ", two-level " << iterations[1];
}

TEST(LinearSolver, CoarseCorrectionIsExactOnRigidMotions) {
  // P A_c^-1 P^T A u = u for every u in the coarse space; rigid motions of the whole free body
  // are in it (each aggregate translates by t + w x c and turns by w). With the coarse system
  // kept dense (425 nodes, 24 aggregates) and sparse (825 nodes, 44 aggregates).
  for (const auto& [cells, dense] :
       {std::pair{Eigen::Vector3i(16, 4, 4), true}, std::pair{Eigen::Vector3i(32, 4, 4), false}}) {
    WarpedSystem system(cells);
    system.constrained.assign(system.mesh.numNodes(), 0);
    const dc::SystemMatrix a = system.matrix();
    dc::RigidModeCoarseSpace coarse(*a.stiffness);
    ASSERT_GT(coarse.numAggregates(), 3);
    ASSERT_EQ(coarse.dense(), dense) << system.mesh.numNodes() << " nodes";
    coarse.refresh(a, system.constrained, system.x);
    const Eigen::VectorXd& x = system.x;
    for (int mode = 0; mode < 6; ++mode) {
      Eigen::VectorXd u(x.size());
      for (int i = 0; i < system.mesh.numNodes(); ++i) {
        const Eigen::Vector3d e = Eigen::Vector3d::Unit(mode % 3);
        u.segment<3>(3 * i) = mode < 3 ? e : Eigen::Vector3d(e.cross(x.segment<3>(3 * i)));
      }
      Eigen::VectorXd r(u.size()), z = Eigen::VectorXd::Zero(u.size());
      a.multiply(u, r);
      coarse.addCorrection(system.constrained, r, z);
      // Exact up to the conditioning of A_c and its tiny regularizing shift.
      EXPECT_NEAR((z - u).norm() / u.norm(), 0.0, 1e-7)
          << "mode " << mode << ", " << system.mesh.numNodes() << " nodes";
    }
  }
}

TEST(SpinBarrier, NoThreadPassesBeforeAllHaveArrivedAndAllSeeWhatEachWrote) {
  // Three threads (more than this machine's cores, so some wait descheduled) meet 2 000 times:
  // each writes its round before a meeting and checks every other's after it; a second meeting
  // keeps the next round's writes from racing the checks.
  constexpr int kThreads = 3, kRounds = 2000;
  dc::SpinBarrier barrier;
  barrier.reset(kThreads);
  std::array<int, kThreads> round{};
  std::atomic<int> mismatches{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      for (int k = 1; k <= kRounds; ++k) {
        round[t] = k;
        barrier.arriveAndWait();
        for (int other : round) mismatches += other != k;
        barrier.arriveAndWait();
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  EXPECT_EQ(mismatches.load(), 0);
}

TEST(DenseCholesky, SolvesAsEigensCholesky) {
  // Sizes around the four-column blocks of the sweeps, and the default scene's coarse size.
  for (int n : {1, 2, 3, 4, 5, 6, 7, 8, 9, 13, 37, 144}) {
    const Eigen::MatrixXd b = Eigen::MatrixXd::Random(n, n);
    const Eigen::MatrixXd spd = b * b.transpose() + n * Eigen::MatrixXd::Identity(n, n);
    const Eigen::VectorXd rhs = Eigen::VectorXd::Random(n);
    const Eigen::VectorXd expected = spd.llt().solve(rhs);
    dc::DenseCholesky cholesky;
    cholesky.resize(n);
    cholesky.matrix().triangularView<Eigen::Lower>() = spd;  // only the lower triangle is read
    ASSERT_TRUE(cholesky.factorize()) << n;
    Eigen::VectorXd x(n);
    cholesky.solve(rhs, x);
    EXPECT_LE((x - expected).norm(), 1e-13 * expected.norm()) << n;
    EXPECT_LE((spd * x - rhs).norm(), 1e-12 * rhs.norm()) << n;
    Eigen::VectorXd in_place = rhs;
    cholesky.solve(in_place, in_place);
    EXPECT_EQ(in_place, x) << n;
  }
  dc::DenseCholesky indefinite;
  indefinite.resize(2);
  indefinite.matrix() << 1.0, 0.0, 2.0, 1.0;  // lower triangle of [1 2; 2 1]
  EXPECT_FALSE(indefinite.factorize());
}

TEST(LinearSolver, CoarseSpaceTakesOneRingOnSmallMeshesAndTwoOnLargerOnes) {
  // The default scene's beam (425 nodes): aggregates of a node and its neighbours; a longer beam
  // (825 nodes) too; the 9k benchmark cantilever (2 025 nodes): of two rings, whose coarse system
  // is far smaller. The coarse systems of 144 and 120 unknowns are kept dense, the one of 264
  // sparse (its factor has under a third of the numbers of its dense triangle).
  for (const auto& [cells, rings, dense] : {std::tuple{Eigen::Vector3i(16, 4, 4), 1, true},
                                            std::tuple{Eigen::Vector3i(32, 4, 4), 1, false},
                                            std::tuple{Eigen::Vector3i(24, 8, 8), 2, true}}) {
    const dc::Mesh mesh = dc::makeBoxMesh({0, -0.1, -0.1}, {0.6, 0.1, 0.1}, cells);
    const dc::BlockSparseMatrix k(dc::nodeNeighbours(mesh));
    const dc::RigidModeCoarseSpace coarse(k);
    EXPECT_EQ(coarse.rings(), rings) << mesh.numNodes() << " nodes";
    EXPECT_EQ(coarse.dense(), dense) << mesh.numNodes() << " nodes";
    // Every node is in an aggregate. One ring lies within the 3 x 3 x 3 grid nodes around its
    // first node, two rings reach out to 5 x 5 x 5: on average fewer and more than 27 nodes.
    for (int g : coarse.aggregateOfNode()) ASSERT_TRUE(g >= 0 && g < coarse.numAggregates());
    if (rings == 1) {
      EXPECT_GT(27 * coarse.numAggregates(), mesh.numNodes());
    } else {
      EXPECT_LT(27 * coarse.numAggregates(), mesh.numNodes());
    }
  }
}

TEST(LinearSolver, StaleCoarseOperatorStillConvergesAfterConstraintsChange) {
  WarpedSystem system;
  dc::ConjugateGradientSolver solver;
  dc::SolverSettings settings = cg(Preconditioner::kTwoLevel);
  settings.coarse_refresh_interval = 1000;  // the coarse operator of the first solve stays
  Eigen::VectorXd x = Eigen::VectorXd::Zero(system.b.size());
  ASSERT_TRUE(solver.solve(system.matrix(), system.constrained, system.b, settings, x).converged);
  // Now also hold the free end, prescribed where it is: the coarse operator still has it free.
  for (int i = 0; i < system.mesh.numNodes(); ++i) {
    if (system.mesh.positions[i].x() > 1.2 - 1e-9) system.constrained[i] = 1;
  }
  const Eigen::VectorXd expected = system.direct();
  x.setZero();
  const dc::SolveReport report =
      solver.solve(system.matrix(), system.constrained, system.b, settings, x);
  EXPECT_TRUE(report.converged);
  EXPECT_NEAR((x - expected).norm() / expected.norm(), 0.0, 1e-8);
}

// The factorization of A as preconditioner: the first solve is exact in one iteration; after the
// rotations change (stale factor, refresh interval not reached) CG still reaches the direct
// solution, in far fewer iterations than the two-level preconditioner; a change of constraints
// refactorizes at once.
TEST(LinearSolver, StaleFactorizationPreconditionsTheNextSolves) {
  WarpedSystem system;
  dc::ConjugateGradientSolver solver;
  dc::SolverSettings settings = cg(Preconditioner::kFactorization);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(system.b.size());
  dc::SolveReport report = solver.solve(system.matrix(), system.constrained, system.b, settings, x);
  EXPECT_TRUE(report.converged);
  EXPECT_LE(report.iterations, 2);

  // Bend it further: new rotations, the old factor.
  Eigen::VectorXd bent = system.x;
  for (int i = 0; i < system.mesh.numNodes(); ++i) {
    const double s = system.mesh.positions[i].x();
    bent.segment<3>(3 * i) =
        Eigen::AngleAxisd(0.5 * s, Eigen::Vector3d::UnitZ()) * system.x.segment<3>(3 * i);
  }
  system.elasticity.update(bent, true);
  const Eigen::VectorXd expected = system.direct();
  x.setZero();
  report = solver.solve(system.matrix(), system.constrained, system.b, settings, x);
  EXPECT_TRUE(report.converged);
  EXPECT_NEAR((x - expected).norm() / expected.norm(), 0.0, 1e-8);
  dc::ConjugateGradientSolver two_level;
  Eigen::VectorXd y = Eigen::VectorXd::Zero(system.b.size());
  const int two_level_iterations =
      two_level
          .solve(system.matrix(), system.constrained, system.b, cg(Preconditioner::kTwoLevel), y)
          .iterations;
  EXPECT_LT(report.iterations, two_level_iterations);
  RecordProperty("stale_factorization_iterations", report.iterations);
  RecordProperty("two_level_iterations", two_level_iterations);

  // Hold the free end too: refactorized, exact again.
  for (int i = 0; i < system.mesh.numNodes(); ++i) {
    if (system.mesh.positions[i].x() > 1.2 - 1e-9) system.constrained[i] = 1;
  }
  const Eigen::VectorXd held = system.direct();
  x.setZero();
  report = solver.solve(system.matrix(), system.constrained, system.b, settings, x);
  EXPECT_LE(report.iterations, 2);
  EXPECT_NEAR((x - held).norm() / held.norm(), 0.0, 1e-8);
}
