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
