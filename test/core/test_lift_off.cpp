// Contact only pushes: a plate that presses a foam cube on a table and lifts away leaves the cube
// where it was; while it rises the force it exerts on the cube never pulls it up, but for the
// friction of a dent's walls that it slides out of, and none once it is clear of the cube.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "body_meters.h"
#include "deformable_sim/core/session/simulation.h"
#include "scene_builder.h"
#include "simulation_test_helpers.h"

namespace dc = deformable_sim::core;
using deformable_sim::test::centreOfMass;

namespace {

constexpr double kSide = 0.06;    // m, the cube
constexpr double kPress = 0.003;  // m the plate goes below the cube's top
constexpr double kPlate = 0.01;   // m, the plate's thickness
constexpr double kRaise = 0.02;   // m the plate rises above the cube's top

struct LiftOff {
  double settled = 0.0;     ///< the cube's centre of mass before the plate comes, m
  double end = 0.0;         ///< where it is at the end, m
  double largest_pull = 0;  ///< the largest upward force of the plate on the cube, N
  /// The same in the steps that start with the plate's bottom above the cube's settled top, N.
  double pull_when_clear = 0;
  double pressing = 0.0;  ///< the plate's push while it presses, N
};

LiftOff pressAndLift(double friction, double plate_width, int lift_steps) {
  dc::SceneSpec spec = deformable_sim::test::dampedTable(friction, {0.4, 0.4, 0.04});
  dc::PlacedShape plate;
  plate.name = "plate";
  plate.shape.kind = dc::Shape::Kind::kBox;
  plate.shape.size = Eigen::Vector3d(plate_width, plate_width, kPlate);
  const auto plateAt = [&](double bottom) {
    plate.pose.translation() = Eigen::Vector3d(0, 0, bottom + 0.5 * kPlate);
    return plate;
  };
  spec.obstacles.push_back(plateAt(kSide + kRaise));
  spec.bodies.push_back(deformable_sim::test::boxBody("cube", {-0.5 * kSide, -0.5 * kSide, 0.0},
                                                      {0.5 * kSide, 0.5 * kSide, kSide}, {4, 4, 4},
                                                      {3.0e4, 0.3, 150.0}));
  dc::Simulation sim = deformable_sim::test::boxMeshSimulation(spec);
  std::vector<dc::StepReport> reports;
  for (int s = 0; s < 100; ++s) sim.step(reports);  // the cube settles on the table
  LiftOff run;
  run.settled = centreOfMass(sim.bodies()[0]).z();
  double top = 0.0;  // the settled cube's top
  const Eigen::VectorXd& x = sim.bodies()[0].positions();
  for (int i = 0; i < sim.bodies()[0].numNodes(); ++i) top = std::max(top, x[3 * i + 2]);
  const auto movePlate = [&](double bottom) { sim.obstacles()[1] = plateAt(bottom); };
  for (int s = 1; s <= 50; ++s) {  // down to kPress into the cube in 0.5 s, and held 0.2 s
    movePlate(top + kRaise - (kRaise + kPress) * s / 50.0);
    sim.step(reports);
  }
  for (int s = 0; s < 20; ++s) sim.step(reports);
  run.pressing = -sim.obstacleContacts(0)[1].force.z();
  for (int s = 1; s <= 150; ++s) {  // up and away in lift_steps, then on to 1.5 s
    const double bottom = sim.obstacles()[1].pose.translation().z() - 0.5 * kPlate;
    if (s <= lift_steps) movePlate(top - kPress + (kRaise + kPress) * s / lift_steps);
    sim.step(reports);
    const double pull = sim.obstacleContacts(0)[1].force.z();
    run.largest_pull = std::max(run.largest_pull, pull);
    if (bottom > top) run.pull_when_clear = std::max(run.pull_when_clear, pull);
  }
  run.end = centreOfMass(sim.bodies()[0]).z();
  return run;
}

// What the plate leaves: the cube back where it settled (its rebound may throw it up for a while:
// foam pressed 3 mm stores enough to jump), and never a pull on it while the plate rises.
void expectLeftWhereItWas(double friction, double width, int lift_steps) {
  const LiftOff run = pressAndLift(friction, width, lift_steps);
  const std::string what = "friction " + std::to_string(friction) + ", plate " +
                           std::to_string(width) + " m, lift in " + std::to_string(lift_steps) +
                           " steps";
  EXPECT_GT(run.pressing, 1.0) << what << ": the plate did not press";
  EXPECT_LT(std::abs(run.end - run.settled), 0.001) << what;
  EXPECT_LE(run.largest_pull, 1e-9) << what;
}

}  // namespace

TEST(LiftOff, APlateWiderOrNarrowerThanTheCubeLiftsAwayWithoutIt) {
  // 10 cm covers the cube; 3.5 and 2.5 cm sink into its top, their sides between its nodes.
  for (double friction : {0.5, 1.0}) {
    for (double width : {0.1, 0.035, 0.025}) {
      for (int lift_steps : {50, 5, 1}) expectLeftWhereItWas(friction, width, lift_steps);
    }
  }
}

// [contact-space] reports it: a plate pressed into a cube's top and lifted away carried the cube
// with it. It did when the plate's sides stood exactly on a column of the cube's nodes (3 cm, the
// cube's 1.5 cm cells): raised 2.3 cm in 0.5 s it left the cube 2.2 cm up at μ = 1.0; in 0.05 s
// 6 mm up at μ = 0.5 and 2.5 cm at μ = 1.0; in 0.01 s 5.3 and 4.3 cm up. The nodes beside the
// plate, pressed against its sides, and those under it made one patch taken whole, whose
// correction was kept along the patch's mean normal, up: the side nodes' slip never came back.
// Now a body on several faces of an obstacle slides on their planes. The walls of the dent drag
// the cube up while the plate slides out of it (friction, up to μ times their push: 2.6 N in the
// step a plate leaves 2.3 cm at once at μ = 1.0), never once the plate is clear of the cube.
TEST(LiftOff, APlateWhoseSidesStandOnNodesLiftsAwayWithoutTheCube) {
  for (double friction : {0.5, 1.0}) {
    for (int lift_steps : {50, 5, 1}) {
      const LiftOff run = pressAndLift(friction, 0.03, lift_steps);
      const std::string what =
          "friction " + std::to_string(friction) + ", lift in " + std::to_string(lift_steps);
      EXPECT_GT(run.pressing, 1.0) << what << ": the plate did not press";
      EXPECT_LT(std::abs(run.end - run.settled), 0.001) << what;
      EXPECT_LE(run.pull_when_clear, 1e-9) << what;
    }
  }
}
