// Obstacles touch a body made from a surface with that surface, not with the grid it was
// voxelized into, whose boundary stands up to a cell outside it: a ball dropped on a floor comes
// to rest on its own surface, the floor carrying its weight, and its grid sinks into the floor.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "deformable_sim/core/session/simulation.h"
#include "deformable_sim/core/surface_bodies/surface_body.h"
#include "scene_builder.h"
#include "simulation_test_helpers.h"
#include "surface_test_helpers.h"

namespace dc = deformable_sim::core;

namespace {

constexpr double kRadius = 0.03;   // m
constexpr double kCell = 0.014;    // m: 5 cells across, the grid stands about 5 mm out
constexpr double kGravity = 9.81;  // m/s^2

struct Rest {
  double lowest_vertex = 0.0;                             ///< m above the floor's top
  double lowest_node = 0.0;                               ///< m, the same for the grid
  Eigen::Vector3d floor_force = Eigen::Vector3d::Zero();  ///< N, on the ball, floor's frame
  double weight = 0.0;                                    ///< N
  int points = 0;
};

// A ball of kRadius made from its surface, dropped from 5 mm above a floor whose top is at z = 0,
// turned by `tilt` about x, after 3 s. Gravity points into the floor, turned with it: a ball on a
// slope rolls off (its contact patch, ~5 mm across, is far too small to hold it on 20°).
Rest dropBall(double tilt) {
  const dc::PlacedShape floor = deformable_sim::test::floorBox({0.4, 0.4, 0.04}, "floor", tilt);
  const Eigen::Vector3d up = floor.pose.linear() * Eigen::Vector3d::UnitZ();
  dc::SceneSpec spec = deformable_sim::test::SceneBuilder()
                           .dt(0.01)
                           .gravity(Eigen::Vector3d(-kGravity * up))
                           .warped()
                           .damping(2.0, 0.002)
                           .contact(1.0)
                           .obstacle(floor);
  dc::BodySpec body;
  body.name = "ball";
  body.material = {3.0e4, 0.3, 150.0};
  spec.bodies.push_back(body);
  dc::VoxelSettings cells;
  cells.cell_size = kCell;
  const Eigen::Vector3d centre = floor.pose.linear() * Eigen::Vector3d(0, 0, kRadius + 0.005);
  dc::SurfaceBody ball = dc::bodyFromSurface(
      deformable_sim::test::sphereSurface(kRadius, centre, 16, 32), cells, nullptr);
  dc::Simulation sim = deformable_sim::test::surfaceSimulation(spec, {std::move(ball)});
  std::vector<dc::StepReport> reports;
  for (int s = 0; s < 300; ++s) sim.step(reports);

  Rest rest;
  rest.lowest_vertex = rest.lowest_node = std::numeric_limits<double>::infinity();
  dc::EmbeddedSurface& surface = *sim.embeddedSurface(0);
  surface.update(sim.bodies()[0].positions());
  for (const Eigen::Vector3d& v : surface.positions()) {
    rest.lowest_vertex = std::min(rest.lowest_vertex, up.dot(v));
  }
  const dc::Body& b = sim.bodies()[0];
  for (int i = 0; i < b.numNodes(); ++i) {
    rest.lowest_node = std::min(rest.lowest_node, up.dot(b.positions().segment<3>(3 * i)));
  }
  rest.floor_force = floor.pose.linear().transpose() * sim.obstacleContacts(0)[0].force;
  rest.points = sim.obstacleContacts(0)[0].points;
  for (double m : b.nodalMasses()) rest.weight += m * kGravity;
  return rest;
}

}  // namespace

TEST(SurfaceContact, ABallMadeFromItsSurfaceRestsOnItsSurfaceNotOnItsGrid) {
  const Rest rest = dropBall(0.0);
  EXPECT_GT(rest.points, 0);
  // Its surface touches the floor: inside by no more than round-off, above by much less than the
  // millimetres its grid stands out.
  EXPECT_GT(rest.lowest_vertex, -1e-6);
  EXPECT_LT(rest.lowest_vertex, 2e-4);
  // The grid's lowest nodes lie in the floor: they only carry the surface.
  EXPECT_LT(rest.lowest_node, -0.002);
  // The floor carries its weight.
  EXPECT_NEAR(rest.floor_force.z(), rest.weight, 0.01 * rest.weight);
  EXPECT_NEAR(rest.floor_force.x(), 0.0, 0.01 * rest.weight);
  EXPECT_NEAR(rest.floor_force.y(), 0.0, 0.01 * rest.weight);
}

TEST(SurfaceContact, OnAFloorTurnedAgainstItsGridItStillRestsOnItsSurface) {
  // Turned 20°, the floor cuts the grid's cells at a slant.
  const Rest rest = dropBall(20.0 * M_PI / 180.0);
  EXPECT_GT(rest.points, 0);
  EXPECT_GT(rest.lowest_vertex, -1e-6);
  EXPECT_LT(rest.lowest_vertex, 2e-4);
  EXPECT_LT(rest.lowest_node, -0.002);
  EXPECT_NEAR(rest.floor_force.z(), rest.weight, 0.01 * rest.weight);
  EXPECT_NEAR(rest.floor_force.head<2>().norm(), 0.0, 0.01 * rest.weight);
}
