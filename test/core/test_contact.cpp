// Shapes and the contact effect: distances to boxes, spheres and cylinders; a block dropped on a
// table comes to rest on top of it.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "deformable_sim/core/contact/contact.h"
#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/geometry/shape.h"
#include "deformable_sim/core/outputs/contact_pairs.h"
#include "deformable_sim/core/session/simulation.h"
#include "scene_builder.h"
#include "simulation_test_helpers.h"

namespace dc = deformable_sim::core;
using deformable_sim::test::boxMeshSimulation;

namespace {

// A block (body "block") above a 1 m x 1 m box table `thickness` thick whose top face is at
// z = 0 (obstacle "table"), under gravity, lightly damped, with contact and friction 0.5.
dc::SceneSpec blockAboveATable(double thickness, const dc::BoxMeshSpec& block_mesh,
                               const dc::LinearElasticMaterial& material) {
  dc::SceneSpec spec = deformable_sim::test::dampedTable(0.5, {1.0, 1.0, thickness});
  dc::BodySpec block;
  block.name = "block";
  block.box_mesh = block_mesh;
  block.material = material;
  spec.bodies.push_back(block);
  return spec;
}

}  // namespace

TEST(Shape, SignedDistancesToTheThreePrimitives) {
  dc::Shape box;
  box.kind = dc::Shape::Kind::kBox;
  box.size = {2.0, 4.0, 6.0};
  Eigen::Vector3d surface, normal;
  EXPECT_DOUBLE_EQ(dc::signedDistance(box, {0.0, 0.0, 2.5}, &surface, &normal), -0.5);
  EXPECT_EQ(surface, Eigen::Vector3d(0.0, 0.0, 3.0));
  EXPECT_EQ(normal, Eigen::Vector3d::UnitZ());
  EXPECT_DOUBLE_EQ(dc::signedDistance(box, {2.0, 3.0, 0.0}, &surface, &normal), std::sqrt(2.0));
  EXPECT_EQ(surface, Eigen::Vector3d(1.0, 2.0, 0.0));
  dc::Shape sphere;
  sphere.kind = dc::Shape::Kind::kSphere;
  sphere.radius = 2.0;
  EXPECT_DOUBLE_EQ(dc::signedDistance(sphere, {0.0, 1.0, 0.0}, &surface, &normal), -1.0);
  EXPECT_EQ(surface, Eigen::Vector3d(0.0, 2.0, 0.0));
  dc::Shape cylinder;
  cylinder.kind = dc::Shape::Kind::kCylinder;
  cylinder.radius = 1.0;
  cylinder.length = 4.0;
  EXPECT_NEAR(dc::signedDistance(cylinder, {0.0, 0.9, 0.0}, &surface, &normal), -0.1, 1e-15);
  EXPECT_TRUE(normal.isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_NEAR(dc::signedDistance(cylinder, {0.0, 0.0, -1.9}, &surface, &normal), -0.1, 1e-15);
  EXPECT_EQ(normal, -Eigen::Vector3d::UnitZ());
  EXPECT_DOUBLE_EQ(dc::signedDistance(cylinder, {0.0, 4.0, 6.0}), 5.0);  // past the rim: 3-4-5
  dc::Shape bad = box;
  bad.size.y() = -1.0;
  EXPECT_THROW(dc::validate(bad, "obstacles[0]"), std::invalid_argument);
}

TEST(Contact, ABlockDroppedOnATableComesToRestOnTop) {
  dc::SceneSpec spec = blockAboveATable(
      0.1, dc::BoxMeshSpec{{-0.05, -0.05, 0.1}, {0.05, 0.05, 0.2}, {4, 4, 4}}, {3.0e4, 0.3, 150.0});
  dc::Simulation sim = boxMeshSimulation(spec);
  std::vector<dc::StepReport> reports;
  for (int s = 0; s < 600; ++s) {
    sim.step(reports);
    const Eigen::VectorXd& x = sim.bodies()[0].positions();
    for (int i = 0; i < sim.bodies()[0].numNodes(); ++i) ASSERT_GE(x[3 * i + 2], -1e-12) << s;
  }
  EXPECT_EQ(reports[0].contacts, 25);  // resting on the bottom face's 5 x 5 nodes
  const dc::Body& body = sim.bodies()[0];
  EXPECT_LT(body.velocities().lpNorm<Eigen::Infinity>(), 1e-3);
  double bottom = 1.0;
  for (int i = 0; i < body.numNodes(); ++i) bottom = std::min(bottom, body.positions()[3 * i + 2]);
  EXPECT_NEAR(bottom, 0.0, 1e-12);
  // The table carries the block through the solve: it is compressed by its own weight only,
  // about rho g H^2 / (2 E) for a column (the held bottom face and Poisson's ratio change that a
  // little), not pushed into itself by the contact.
  double top = 0.0;
  for (int i = 0; i < body.numNodes(); ++i) top = std::max(top, body.positions()[3 * i + 2]);
  const double column = 150.0 * 9.81 * 0.1 * 0.1 / (2 * 3.0e4);
  EXPECT_GT(0.1 - top, 0.5 * column);
  EXPECT_LT(0.1 - top, 2.0 * column);
  // Without the contact effect the same block falls through.
  spec.contact.reset();
  spec.obstacles.clear();
  dc::Simulation free_fall = boxMeshSimulation(spec);
  for (int s = 0; s < 60; ++s) free_fall.step(reports);
  EXPECT_EQ(reports[0].contacts, 0);
  EXPECT_LT(free_fall.bodies()[0].positions().maxCoeff(), 1.0);
  double lowest = 1.0;
  for (int i = 0; i < free_fall.bodies()[0].numNodes(); ++i) {
    lowest = std::min(lowest, free_fall.bodies()[0].positions()[3 * i + 2]);
  }
  EXPECT_LT(lowest, -0.5);
}

namespace {

// A stiff 10 cm block falling at 3 m/s just above a table top 3 cm thick.
dc::Simulation blockFallingFastOnAThinTable() {
  dc::Simulation sim = boxMeshSimulation(
      blockAboveATable(0.03, dc::BoxMeshSpec{{-0.05, -0.05, 0.002}, {0.05, 0.05, 0.102}, {2, 2, 2}},
                       {1.0e6, 0.3, 500.0}));
  dc::Body& body = sim.bodies()[0];
  body.setState(body.positions(), Eigen::Vector3d(0, 0, -3.0).replicate(body.numNodes(), 1));
  return sim;
}

}  // namespace

// A thin table top (3 cm, as URDF tables often are) hit fast: a block falling at 3 m/s crosses
// 3 cm in a 0.01 s step and its bottom nodes are found past the middle of the top, nearest to its
// underside. They go back out by the face they came in through and the block rests on top.
TEST(Contact, ABlockHittingAThinTableFastStaysOnTop) {
  dc::Simulation sim = blockFallingFastOnAThinTable();
  dc::Body& body = sim.bodies()[0];
  std::vector<dc::StepReport> reports;
  sim.step(reports);
  EXPECT_GT(sim.obstacleContacts(0)[0].penetration, 0.015);  // past the middle of the top
  for (int s = 0; s < 100; ++s) sim.step(reports);
  for (int i = 0; i < body.numNodes(); ++i) EXPECT_GE(body.positions()[3 * i + 2], -1e-9) << i;
  EXPECT_EQ(reports[0].contacts, 9);  // resting on its bottom face's 3 x 3 nodes
}

// ~contacts tells the two depths apart: how deep the fast block's nodes were found inside the
// table top (past its middle), and how deep they are after the step put them back (not at all).
TEST(Contact, APairsDepthIsWhatTheStepLeftItsPenetrationWhatItCorrected) {
  dc::Simulation sim = blockFallingFastOnAThinTable();
  std::vector<dc::StepReport> reports;
  std::vector<dc::ContactPair> pairs;
  int touching = 0;
  for (int s = 0; s < 100; ++s) {
    sim.step(reports);
    dc::touchingPairs(sim, pairs);
    ASSERT_LE(pairs.size(), 1u) << "step " << s;
    if (s == 0) {
      ASSERT_EQ(pairs.size(), 1u);
      EXPECT_GT(pairs[0].load.penetration, 0.015);
    }
    if (pairs.empty()) continue;  // in the air after the blow
    ++touching;
    EXPECT_GE(pairs[0].load.depth, 0.0);
    EXPECT_LE(pairs[0].load.depth, 1e-9) << "step " << s;
  }
  EXPECT_GT(touching, 50);  // and at rest on the table
}

// What a resting block feels from a table made of two boxes of one name (a URDF link's two
// collision shapes): one pair, carrying its weight at the middle of its bottom face, and the
// table feels the opposite.
TEST(Contact, PairsMergeShapesOfOneNameAndCarryTheWeight) {
  dc::SceneSpec spec = blockAboveATable(
      0.1, dc::BoxMeshSpec{{-0.05, -0.05, 0.0}, {0.05, 0.05, 0.1}, {4, 4, 4}}, {3.0e4, 0.3, 150.0});
  spec.obstacles.clear();
  for (double x : {-0.245, 0.245}) {  // two boards overlapping by 1 cm, tops at z = 0
    dc::PlacedShape half;
    half.name = "table";
    half.shape.size = {0.5, 1.0, 0.1};
    half.pose.translation() = Eigen::Vector3d(x, 0.0, -0.05);
    spec.obstacles.push_back(half);
  }
  dc::Simulation sim = boxMeshSimulation(spec);
  std::vector<dc::StepReport> reports;
  for (int s = 0; s < 300; ++s) sim.step(reports);
  std::vector<dc::ContactPair> pairs;
  dc::touchingPairs(sim, pairs);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0].kind, dc::ContactPair::Kind::kObstacle);
  EXPECT_EQ(pairs[0].other, "table");
  EXPECT_EQ(pairs[0].load.points, 25);
  const double weight = 150.0 * 0.1 * 0.1 * 0.1 * 9.81;
  EXPECT_NEAR(pairs[0].load.force.z(), weight, 1e-6 * weight);
  EXPECT_NEAR(pairs[0].load.force.head<2>().norm(), 0.0, 1e-9);
  EXPECT_NEAR(pairs[0].load.centre.head<2>().norm(), 0.0, 1e-9);
  EXPECT_NEAR(pairs[0].load.centre.z(), 0.0, 1e-12);
  // Its torque about the world origin is that of a force at the centre of the face.
  EXPECT_NEAR((pairs[0].load.torque - pairs[0].load.centre.cross(pairs[0].load.force)).norm(), 0.0,
              1e-9);
  const dc::ContactLoad on_table = dc::loadOnObstacle(pairs, "table");
  EXPECT_TRUE(on_table.force.isApprox(-pairs[0].load.force));
  EXPECT_EQ(on_table.points, 25);
  EXPECT_TRUE(dc::loadOnObstacle(pairs, "nothing").force.isZero(0.0));
}
