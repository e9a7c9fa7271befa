// The order of a contact step (core/contact_step.h): which bodies it acts on, what it counts, and
// where it says a step's contact time went.
#include <gtest/gtest.h>

#include "deformable_sim/core/contact/contact_step.h"
#include "deformable_sim/core/session/simulation.h"
#include "scene_builder.h"
#include "simulation_test_helpers.h"

namespace dc = deformable_sim::core;

namespace {

dc::BodySpec cube(const std::string& name, const Eigen::Vector3d& min, dc::BodyModel model) {
  return deformable_sim::test::boxBody(name, min, min + Eigen::Vector3d::Constant(0.1), {2, 2, 2},
                                       {1.0e5, 0.3, 100.0}, model);
}

// On a floor: a soft cube with a rigid one resting on it, and a soft one beside them that keeps
// out of contact between bodies (its own effects).
dc::Simulation floorWithThreeCubes() {
  dc::SceneSpec spec = deformable_sim::test::sceneOnAFloor(true);
  spec.bodies = {cube("soft", {-0.05, -0.05, 0.0}, dc::BodyModel::kFiniteElement),
                 cube("rigid", {-0.05, -0.05, 0.1}, dc::BodyModel::kRigid),
                 cube("apart", {0.3, 0.0, 0.0}, dc::BodyModel::kFiniteElement)};
  spec.bodies[2].effects = spec.effects;
  spec.bodies[2].effects->contact_bodies = false;
  return deformable_sim::test::boxMeshSimulation(spec);
}

}  // namespace

TEST(ContactStep, ObstaclesHoldFiniteElementBodiesOnlyBodiesMeetWhereBothAsk) {
  dc::Simulation sim = floorWithThreeCubes();
  std::vector<dc::StepReport> reports;
  for (int s = 0; s < 20; ++s) sim.step(reports);
  EXPECT_GT(sim.obstacleContacts(0).at(0).points, 0);  // the soft cube on the floor
  EXPECT_TRUE(sim.obstacleContacts(1).empty());        // rigid: no obstacle contact
  EXPECT_GT(sim.obstacleContacts(2).at(0).points, 0);
  EXPECT_EQ(sim.contactSteps(), 2 * 20);  // the two soft bodies' steps
  EXPECT_EQ(sim.bodyContactSteps(), 20);
  ASSERT_NE(sim.bodyContact(), nullptr);
  EXPECT_TRUE(sim.bodyContact()->takesPart(0));
  EXPECT_TRUE(sim.bodyContact()->takesPart(1));
  EXPECT_FALSE(sim.bodyContact()->takesPart(2));
  EXPECT_GT(sim.bodyContact()->load(1, 0).points, 0);  // the rigid cube rests on the soft one
  EXPECT_EQ(sim.bodyContact()->load(2, 0).points, 0);
}

// Each body's contact time: its own with the obstacles, and an equal share of the contact between
// bodies for those that take part.
TEST(ContactStep, SaysWhereEachBodysContactTimeWent) {
  dc::Simulation sim = floorWithThreeCubes();
  std::vector<dc::StepReport> reports;
  for (int s = 0; s < 5; ++s) sim.step(reports);
  EXPECT_GT(reports[0].times.obstacle_contact, 0.0);
  EXPECT_EQ(reports[1].times.obstacle_contact, 0.0);
  EXPECT_GT(reports[2].times.obstacle_contact, 0.0);
  EXPECT_GT(reports[0].times.body_contact, 0.0);
  EXPECT_EQ(reports[0].times.body_contact, reports[1].times.body_contact);
  EXPECT_EQ(reports[2].times.body_contact, 0.0);
}

// Without the effect there is nothing to order: no contact, no counters, no time.
TEST(ContactStep, IsNotThereWithoutTheContactEffect) {
  dc::SceneSpec spec;
  spec.bodies = {cube("soft", {0.0, 0.0, 0.0}, dc::BodyModel::kFiniteElement)};
  dc::Simulation sim = deformable_sim::test::boxMeshSimulation(spec);
  std::vector<dc::StepReport> reports;
  sim.step(reports);
  EXPECT_TRUE(sim.obstacleContacts(0).empty());
  EXPECT_EQ(sim.contactSteps(), 0);
  EXPECT_EQ(sim.bodyContact(), nullptr);
  EXPECT_EQ(reports[0].times.obstacle_contact + reports[0].times.body_contact, 0.0);
}
