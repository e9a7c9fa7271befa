// Shipped surface objects at rest: alone on a floor, and in a pile.
//
// A body at rest on a floor costs one solve a step. Its rotations still turn by micro-radians a
// step, and the energy that adds was once judged against a round-off of 1e-12 of the body's
// energy: the shipped ball (config/meshes/ball.stl) resting on a floor gained 5e-9 of it, solved
// its step again and split it to the limit, 254 solves and 0.3 s a step
// (FiniteElementBody::checkRotationEnergy).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "deformable_sim/core/session/simulation.h"
#include "deformable_sim/io/scene_file.h"

namespace dc = deformable_sim::core;
namespace dio = deformable_sim::io;

namespace {

// The ball of config/scenes/soft_objects.yaml alone on its floor.
const char* const kBallOnFloor = R"(
dt: 0.01
effects:
  gravity: [0.0, 0.0, -9.81]
  warping: true
  damping: {mass: 2.0, stiffness: 0.005}
  contact: {friction: 0.6}
obstacles:
  - {name: floor, box: {size: [0.6, 0.4, 0.02]}, position: [0.0, 0.0, -0.01]}
bodies:
  - name: ball
    mesh: {surface: ../meshes/ball.stl, cells: 10, position: [0.0, 0.0, 0.04]}
    material: {youngs_modulus: 5.0e4, poisson_ratio: 0.45, density: 300.0}
)";

}  // namespace

TEST(RestOnFloor, TheShippedBallSolvesEachStepOnce) {
  const std::string scenes = std::string(DEFORMABLE_SIM_SOURCE_DIR) + "/config/scenes";
  dc::Simulation sim =
      dio::buildSimulation(dio::parseScene(kBallOnFloor, "ball.yaml", scenes), nullptr);
  std::vector<dc::StepReport> reports;
  int again = 0, splits = 0;
  for (int s = 0; s < 120; ++s) {
    sim.step(reports);
    if (s < 50) continue;  // landed and settled
    again += reports[0].solves - 1;
    splits += reports[0].splits;
  }
  EXPECT_EQ(again, 0);
  EXPECT_EQ(splits, 0);
  EXPECT_GT(reports[0].contacts, 0);
  EXPECT_LT(sim.bodies()[0].kineticEnergy(), 1e-9);
}

// config/scenes/pile.yaml: three sponges crossed on a floor, a ball on top and a tube against the
// bottom one, all made from surfaces and touching each other. It stands: each body settles by
// less than a few millimetres, and each rests on what it was put on.
TEST(RestOnFloor, TheShippedPileStands) {
  dc::Simulation sim = dio::buildSimulation(
      dio::readSceneFile(std::string(DEFORMABLE_SIM_SOURCE_DIR) + "/config/scenes/pile.yaml"),
      nullptr);
  const auto centre = [&](int b) {
    const Eigen::VectorXd& x = sim.bodies()[b].positions();
    return Eigen::Vector3d(x.reshaped(3, x.size() / 3).rowwise().mean());
  };
  std::vector<Eigen::Vector3d> start;
  for (int b = 0; b < static_cast<int>(sim.bodies().size()); ++b) start.push_back(centre(b));
  std::vector<dc::StepReport> reports;
  for (int s = 0; s < 150; ++s) sim.step(reports);
  ASSERT_EQ(sim.bodies().size(), 5u);
  for (int b = 0; b < 5; ++b) {
    EXPECT_LT((centre(b) - start[b]).norm(), 0.01) << sim.bodies()[b].name();
    EXPECT_GT(reports[b].body_contacts, 0) << sim.bodies()[b].name();
    EXPECT_LT(sim.bodies()[b].kineticEnergy(), 1e-6) << sim.bodies()[b].name();
  }
  const double tolerance = sim.bodyContact()->tolerance(0, 1);
  for (int b = 0; b < 5; ++b) EXPECT_LE(reports[b].body_penetration, tolerance);
}
