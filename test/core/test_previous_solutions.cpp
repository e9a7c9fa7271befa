// The projected warm start: the stored solutions of a sequence of systems combine into the
// solution of any right-hand side in the span of theirs; the oldest pair gives way when full;
// a cleared store behaves as a new one, bit for bit; constrained entries are left alone. On a
// beam pushed about by changing loads it saves iterations, not accuracy.
#include <gtest/gtest.h>

#include <cmath>

#include "deformable_sim/core/bodies/finite_element_body.h"
#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/elements/selection.h"
#include "deformable_sim/core/solvers/previous_solutions.h"

namespace dc = deformable_sim::core;

namespace {

// Stores the pair (x, b) as the solver does: a guess for b, then its solution.
void store(dc::PreviousSolutions& previous, const Eigen::VectorXd& x, const Eigen::VectorXd& b,
           const std::vector<std::uint8_t>& constrained) {
  Eigen::VectorXd scratch = x;
  previous.guess(b, constrained, scratch);
  previous.add(x, constrained);
}

// A symmetric positive definite matrix of 3 n unknowns.
Eigen::MatrixXd spd(int nodes) {
  const Eigen::MatrixXd b = Eigen::MatrixXd::Random(3 * nodes, 3 * nodes);
  return b * b.transpose() + 3.0 * nodes * Eigen::MatrixXd::Identity(3 * nodes, 3 * nodes);
}

}  // namespace

TEST(PreviousSolutions, CombineIntoTheSolutionOfARightHandSideTheirsSpan) {
  const int nodes = 6;
  const Eigen::MatrixXd a = spd(nodes);
  const std::vector<std::uint8_t> free(nodes, 0);
  dc::PreviousSolutions previous;
  previous.reserve(4, 3 * nodes);
  Eigen::VectorXd x = Eigen::VectorXd::Constant(3 * nodes, 7.0);
  EXPECT_FALSE(previous.guess(Eigen::VectorXd::Ones(3 * nodes), free, x));  // none stored
  EXPECT_EQ(x, Eigen::VectorXd::Constant(3 * nodes, 7.0));
  std::vector<Eigen::VectorXd> solutions;
  for (int k = 0; k < 3; ++k) {
    solutions.push_back(Eigen::VectorXd::Random(3 * nodes));
    store(previous, solutions.back(), a * solutions.back(), free);
  }
  store(previous, Eigen::VectorXd::Ones(3 * nodes), Eigen::VectorXd::Zero(3 * nodes), free);
  EXPECT_EQ(previous.count(), 3);  // a zero right-hand side says nothing: not stored
  const Eigen::VectorXd expected = 0.5 * solutions[0] - 2.0 * solutions[1] + solutions[2];
  ASSERT_TRUE(previous.guess(a * expected, free, x));
  EXPECT_LT((x - expected).norm(), 1e-8 * expected.norm());
  // Outside their span: the best fit, whose residual is orthogonal to the stored b.
  const Eigen::VectorXd b = Eigen::VectorXd::Random(3 * nodes);
  ASSERT_TRUE(previous.guess(b, free, x));
  for (const Eigen::VectorXd& s : solutions) {
    EXPECT_NEAR((a * s).dot(b - a * x), 0.0, 1e-9 * (a * s).norm() * b.norm());
  }
}

TEST(PreviousSolutions, TheOldestGivesWayWhenFull) {
  const int nodes = 4;
  const Eigen::MatrixXd a = spd(nodes);
  const std::vector<std::uint8_t> free(nodes, 0);
  dc::PreviousSolutions previous;
  previous.reserve(2, 3 * nodes);
  std::vector<Eigen::VectorXd> solutions;
  for (int k = 0; k < 3; ++k) {
    solutions.push_back(Eigen::VectorXd::Random(3 * nodes));
    store(previous, solutions.back(), a * solutions.back(), free);
  }
  EXPECT_EQ(previous.count(), 2);
  Eigen::VectorXd x(3 * nodes);
  // The two newest are exact; the first is gone (only fitted).
  for (int k : {1, 2}) {
    ASSERT_TRUE(previous.guess(a * solutions[k], free, x));
    EXPECT_LT((x - solutions[k]).norm(), 1e-8 * solutions[k].norm()) << k;
  }
  ASSERT_TRUE(previous.guess(a * solutions[0], free, x));
  EXPECT_GT((x - solutions[0]).norm(), 1e-3 * solutions[0].norm());
}

TEST(PreviousSolutions, AClearedStoreIsANewOneBitForBit) {
  const int nodes = 5;
  const Eigen::MatrixXd a = spd(nodes);
  const std::vector<std::uint8_t> free(nodes, 0);
  dc::PreviousSolutions used, fresh;
  used.reserve(3, 3 * nodes);
  fresh.reserve(3, 3 * nodes);
  for (int k = 0; k < 4; ++k) {  // fills and wraps around
    const Eigen::VectorXd s = Eigen::VectorXd::Random(3 * nodes);
    store(used, s, a * s, free);
  }
  used.clear();
  EXPECT_EQ(used.count(), 0);
  for (int k = 0; k < 2; ++k) {
    const Eigen::VectorXd s = Eigen::VectorXd::Random(3 * nodes);
    store(used, s, a * s, free);
    store(fresh, s, a * s, free);
  }
  const Eigen::VectorXd b = Eigen::VectorXd::Random(3 * nodes);
  Eigen::VectorXd x_used(3 * nodes), x_fresh(3 * nodes);
  ASSERT_TRUE(used.guess(b, free, x_used));
  ASSERT_TRUE(fresh.guess(b, free, x_fresh));
  EXPECT_EQ(x_used, x_fresh);
}

TEST(PreviousSolutions, ConstrainedEntriesAreLeftAlone) {
  const int nodes = 3;
  const Eigen::MatrixXd a = spd(nodes);
  const std::vector<std::uint8_t> constrained{0, 1, 0};
  dc::PreviousSolutions previous;
  previous.reserve(2, 3 * nodes);
  const Eigen::VectorXd s = Eigen::VectorXd::Random(3 * nodes);
  store(previous, s, a * s, constrained);
  Eigen::VectorXd x = Eigen::VectorXd::Constant(3 * nodes, 9.0);
  ASSERT_TRUE(previous.guess(a * s, constrained, x));
  EXPECT_EQ(x.segment<3>(3), Eigen::Vector3d::Constant(9.0));  // the prescribed value stays
  EXPECT_NE(x.segment<3>(0), Eigen::Vector3d::Constant(9.0));
}

TEST(PreviousSolutions, APushedBeamTakesFewerIterationsToTheSameMotion) {
  // The default scene's beam, clamped, its tip pushed by a load that changes every five steps.
  const auto push = [](dc::SolverSettings::WarmStart warm_start, int& total_iterations) {
    dc::SolverSettings solver;
    solver.warm_start = warm_start;
    dc::BodyEffects effects;
    effects.warping = true;
    effects.gravity = Eigen::Vector3d(0, 0, -9.81);
    effects.damping = dc::RayleighDamping{1.0, 0.002};
    dc::FiniteElementBody body("beam",
                               dc::makeBoxMesh({0, -0.05, -0.05}, {0.5, 0.05, 0.05}, {16, 4, 4}),
                               {1e5, 0.3, 100.0}, effects, solver);
    dc::NodeSelection clamp;
    clamp.kind = dc::NodeSelection::Kind::kBox;
    clamp.box = {{-1e-6, -1, -1}, {1e-6, 1, 1}};
    body.fixNodes(dc::selectNodes(body.mesh(), clamp));
    total_iterations = 0;
    for (int s = 0; s < 300; ++s) {
      if (s % 5 == 0) {
        const double w = std::sin(2.0 * M_PI * 0.4 * 0.01 * s);
        for (int i = 0; i < body.numNodes(); ++i) {
          if (body.restPositions()[3 * i] > 0.4999) {
            body.externalForces().segment<3>(3 * i) = Eigen::Vector3d(0, 0.06, 0.02) * w;
          }
        }
      }
      const dc::StepReport report = body.step(0.01);
      EXPECT_TRUE(report.solve.converged);
      total_iterations += report.solve.iterations;
    }
    return Eigen::VectorXd(body.positions() - body.restPositions());
  };
  int projected_iterations = 0, extrapolated_iterations = 0;
  const Eigen::VectorXd projected =
      push(dc::SolverSettings::WarmStart::kProjected, projected_iterations);
  const Eigen::VectorXd extrapolated =
      push(dc::SolverSettings::WarmStart::kExtrapolated, extrapolated_iterations);
  RecordProperty("projected_iterations", projected_iterations);
  RecordProperty("extrapolated_iterations", extrapolated_iterations);
  EXPECT_LT(projected_iterations, 0.8 * extrapolated_iterations)  // measured: 0.71
      << projected_iterations << " against " << extrapolated_iterations;
  EXPECT_LT((projected - extrapolated).norm(), 1e-4 * extrapolated.norm());
}

TEST(PreviousSolutions, TheSameBitsOnAnyThreadCount) {
  // 1 000 nodes: four chunks of partial sums.
  const int n = 3000;
  const std::vector<std::uint8_t> free(n / 3, 0);
  dc::PreviousSolutions one, two;
  one.reserve(8, n);
  two.reserve(8, n);
  Eigen::VectorXd x_one = Eigen::VectorXd::Zero(n), x_two = Eigen::VectorXd::Zero(n);
  for (int k = 0; k < 12; ++k) {
    const Eigen::VectorXd b = Eigen::VectorXd::Random(n), s = Eigen::VectorXd::Random(n);
    EXPECT_EQ(one.guess(b, free, x_one, 1), k > 0);
    EXPECT_EQ(two.guess(b, free, x_two, 2), k > 0);
    EXPECT_EQ(x_one, x_two) << k;
    one.add(s, free);
    two.add(s, free);
  }
  EXPECT_EQ(one.count(), 8);
}

TEST(PreviousSolutions, NothingIsStoredWithoutAGuess) {
  const std::vector<std::uint8_t> free(2, 0);
  dc::PreviousSolutions previous;
  previous.reserve(4, 6);
  previous.add(Eigen::VectorXd::Ones(6), free);
  EXPECT_EQ(previous.count(), 0);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(6);
  previous.guess(Eigen::VectorXd::Ones(6), free, x);
  previous.add(Eigen::VectorXd::Ones(6), free);
  previous.add(Eigen::VectorXd::Ones(6), free);  // the guess's b is stored once only
  EXPECT_EQ(previous.count(), 1);
}
