// The step's end-of-step rotations: when a step is solved again, what it costs when it is not,
// and the energy a single solve with the start rotations would gain.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "deformable_sim/core/bodies/finite_element_body.h"
#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/elements/selection.h"

namespace dc = deformable_sim::core;

namespace {

dc::BodyEffects warped() {
  dc::BodyEffects effects;
  effects.warping = true;
  return effects;
}

/// A 2 cm steel cube spinning about z at `spin` rad/s, free, no gravity.
dc::FiniteElementBody spinningSteelCube(double spin, const dc::SolverSettings& solver) {
  dc::FiniteElementBody body("cube",
                             dc::makeBoxMesh({-0.01, -0.01, -0.01}, {0.01, 0.01, 0.01}, {2, 2, 2}),
                             {2.0e11, 0.3, 7850.0}, warped(), solver);
  Eigen::VectorXd v(body.restPositions().size());
  for (int i = 0; i < body.numNodes(); ++i) {
    v.segment<3>(3 * i) =
        Eigen::Vector3d(0, 0, spin).cross(Eigen::Vector3d(body.restPositions().segment<3>(3 * i)));
  }
  body.setState(body.restPositions(), v);
  return body;
}

double totalEnergy(const dc::Body& body) { return body.kineticEnergy() + body.elasticEnergy(); }

}  // namespace

// A cantilever swinging down under gravity loses energy in every step (implicit Euler), so no
// step needs a second solve; the rotations are still updated every step.
TEST(EndRotations, ASwingingCantileverIsSolvedOnceAStep) {
  dc::BodyEffects effects = warped();
  effects.gravity = Eigen::Vector3d(0, 0, -9.81);
  dc::FiniteElementBody body("beam",
                             dc::makeBoxMesh({0, -0.05, -0.05}, {1, 0.05, 0.05}, {10, 2, 2}),
                             {1e5, 0.3, 1000}, effects, dc::SolverSettings{});
  dc::NodeSelection clamp;
  clamp.kind = dc::NodeSelection::Kind::kBox;
  clamp.box = {{-1e-9, -1, -1}, {1e-9, 1, 1}};
  body.fixNodes(dc::selectNodes(body.mesh(), clamp));
  double largest_turn = 0.0;
  for (int s = 0; s < 100; ++s) {
    const dc::StepReport report = body.step(0.01);
    ASSERT_EQ(report.solves, 1) << "step " << s;
    EXPECT_EQ(report.splits, 0);
    largest_turn = std::max(largest_turn, report.largest_rotation_change);
  }
  EXPECT_GT(largest_turn, 1e-3);  // it did swing: elements turned within steps
  EXPECT_EQ(body.effectCounters().warping, 100);
}

// dt = 1/30 s on a spinning steel cube (0.17 rad a step): a single solve with the rotations of the
// step's start stores the stretch of x + h v as strain, more than the spin's energy; solved
// again with the end rotations (the default), the energy never rises.
TEST(EndRotations, SpinningSteelGainsEnergyOnlyWithoutThem) {
  for (const int updates : {0, dc::SolverSettings{}.max_rotation_updates}) {
    dc::SolverSettings solver;
    solver.max_rotation_updates = updates;
    dc::FiniteElementBody body = spinningSteelCube(5.0, solver);
    const double e0 = totalEnergy(body);
    double largest = e0;
    int solves = 0;
    for (int s = 0; s < 30; ++s) {
      const dc::StepReport report = body.step(1.0 / 30.0);
      ASSERT_TRUE(body.positions().allFinite());
      solves += report.solves;
      largest = std::max(largest, totalEnergy(body));
    }
    if (updates == 0) {
      EXPECT_EQ(solves, 30);
      EXPECT_GT(largest, 2.0 * e0);
    } else {
      EXPECT_GT(solves, 30);  // steps were solved again
      EXPECT_LE(largest, e0 * (1.0 + 1e-9));
    }
  }
}

// The body's elastic energy after a step is that of its end rotations, the same as a fresh
// computation from its positions.
TEST(EndRotations, ElasticEnergyIsThatOfThePositions) {
  dc::FiniteElementBody body = spinningSteelCube(5.0, dc::SolverSettings{});
  body.mutableVelocities() *= 2.0;
  for (int s = 0; s < 5; ++s) body.step(1.0 / 30.0);
  dc::CorotationalElasticity fresh(body.mesh(), body.settings().material);
  fresh.updateRotations(body.positions());
  EXPECT_NEAR(body.elasticEnergy(), fresh.elasticEnergy(body.positions()),
              1e-12 * totalEnergy(body));
  EXPECT_GT(body.elasticEnergy(), 0.0);
}

// Solved again or not, a step gives the same bits on one thread and on two.
TEST(EndRotations, SameBitsOnAnyThreadCount) {
  Eigen::VectorXd positions[2];
  for (int threads : {1, 2}) {
    dc::SolverSettings solver;
    solver.threads = threads;
    dc::FiniteElementBody body = spinningSteelCube(5.0, solver);
    int solves = 0;
    for (int s = 0; s < 10; ++s) solves += body.step(1.0 / 30.0).solves;
    EXPECT_GT(solves, 10);
    positions[threads - 1] = body.positions();
  }
  EXPECT_EQ(positions[0], positions[1]);
}
