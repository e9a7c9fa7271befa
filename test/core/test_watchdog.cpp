// The watchdog of Simulation::step: a step that leaves a non-finite value, or whose energy leaps
// past what could have put it in, is undone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/session/default_scene.h"
#include "deformable_sim/core/session/simulation.h"
#include "simulation_test_helpers.h"

namespace dc = deformable_sim::core;
using deformable_sim::test::boxMeshSimulation;
using deformable_sim::test::defaultSimulation;

TEST(Watchdog, UndoesANonFiniteStepAndTheBodyCarriesOn) {
  dc::Simulation sim = defaultSimulation();
  std::vector<dc::StepReport> reports;
  for (int s = 0; s < 20; ++s) sim.step(reports);
  dc::Body& body = sim.bodies()[0];
  ASSERT_GT(body.velocities().norm(), 0.0);  // sagging: a moving state to be rescued
  const Eigen::VectorXd before = body.positions();

  // A NaN force that got past every check (the core API does not validate this vector).
  const int tip = body.numNodes() - 1;
  body.externalForces()[3 * tip + 2] = std::numeric_limits<double>::quiet_NaN();
  sim.step(reports);
  EXPECT_TRUE(reports[0].recovered);
  EXPECT_EQ(sim.recoveries(0), 1);
  EXPECT_EQ(body.positions(), before);  // the last good state, exactly
  EXPECT_EQ(body.velocities().norm(), 0.0);
  EXPECT_TRUE(body.positions().allFinite());

  // With the bad force gone, the body simply goes on: finite, solved, sagging again.
  body.externalForces()[3 * tip + 2] = 0.0;
  for (int s = 0; s < 30; ++s) {
    sim.step(reports);
    EXPECT_FALSE(reports[0].recovered) << "step " << s;
    EXPECT_TRUE(reports[0].solve.converged) << "step " << s;
  }
  EXPECT_EQ(sim.recoveries(0), 1);
  EXPECT_TRUE(body.positions().allFinite());
  EXPECT_GT(body.velocities().norm(), 0.0);
}

// Found by fuzzing: a step the watchdog undid left its constraint forces behind, NaN or infinite
// (a box mesh 1e300 m tall; a dt of 5e-324 s, where finite positions came with infinite forces),
// and the node publishes them. They are checked and cleared with the rest.
TEST(Watchdog, UndoneStepLeavesNoNonFiniteConstraintForce) {
  dc::SceneSpec spec = dc::defaultScene();
  spec.bodies[0].box_mesh->max.z() = 1e300;
  dc::Simulation sim = boxMeshSimulation(spec);
  const dc::Body& body = sim.bodies()[0];
  const Eigen::VectorXd before = body.positions();
  std::vector<dc::StepReport> reports;
  for (int s = 0; s < 3; ++s) {
    sim.step(reports);
    EXPECT_TRUE(reports[0].recovered);
    EXPECT_EQ(body.positions(), before);
    EXPECT_TRUE(body.velocities().allFinite());
    EXPECT_TRUE(body.reactionForces().allFinite());
  }
}

TEST(Watchdog, LeavesGoodStepsAlone) {
  dc::Simulation sim = defaultSimulation();
  std::vector<dc::StepReport> reports;
  for (int s = 0; s < 50; ++s) {
    sim.step(reports);
    EXPECT_FALSE(reports[0].recovered);
  }
  EXPECT_EQ(sim.recoveries(0), 0);
}

// The energy check (core/session/energy_watch.h) judges a step by what could have put energy in:
// a clamp yanked 5 cm in one step (its constraint forces work on the beam) and the beam then let
// go (its elastic energy turning into motion) are inputs and releases, not leaps.
TEST(Watchdog, EnergyCheckLeavesAYankedClampAndItsReleaseAlone) {
  dc::Simulation sim = defaultSimulation();
  dc::Body& body = sim.bodies()[0];
  std::vector<int> clamp;
  for (int i = 0; i < body.numNodes(); ++i) {
    if (body.isConstrained(i)) clamp.push_back(i);
  }
  ASSERT_FALSE(clamp.empty());
  std::vector<Eigen::Vector3d> lifted;
  for (int i : clamp)
    lifted.push_back(body.positions().segment<3>(3 * i) + Eigen::Vector3d(0, 0, 0.05));
  std::vector<dc::StepReport> reports;
  body.setNodeTargets(clamp, lifted);
  double most = 0.0;
  for (int s = 0; s < 100; ++s) {
    if (s == 10) body.releaseNodes(clamp);
    sim.step(reports);
    EXPECT_FALSE(reports[0].recovered) << "step " << s;
    most = std::max(most, body.elasticEnergy());
  }
  EXPECT_GT(most, 1e-3);  // really yanked: the beam bent by it
  EXPECT_EQ(sim.recoveries(0), 0);
}

// A linear body's energy as the energy check takes it (one product with K) is the per-element
// sum its elastic energy reports, wherever the body does not turn.
TEST(Watchdog, EnergyCheckTakesALinearBodysEnergyAsItsElementsSumIt) {
  dc::SceneSpec spec = dc::defaultScene();
  spec.effects.warping = false;
  dc::Simulation sim = boxMeshSimulation(spec);
  std::vector<dc::StepReport> reports;
  for (int s = 0; s < 20; ++s) sim.step(reports);
  const dc::Body& body = sim.bodies()[0];
  ASSERT_FALSE(body.settings().effects.warping);
  const double elastic = body.elasticEnergy();
  ASSERT_GT(elastic, 1e-6);  // sagging
  dc::EnergyWatch watch(sim.bodies());
  EXPECT_NEAR(watch.energy(body, 0), body.kineticEnergy() + elastic, 1e-3 * elastic);
}
