// Wrench distribution, best-fit frames and the command processor: what the node does with a
// message, checked without ROS.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <limits>

#include "deformable_sim/core/bodies/rigid_frame.h"
#include "deformable_sim/core/bodies/wrench.h"
#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/outputs/body_activity.h"
#include "deformable_sim/core/session/commands.h"
#include "deformable_sim/core/session/default_scene.h"
#include "deformable_sim/core/session/session.h"
#include "deformable_sim/core/session/simulation.h"
#include "deformable_sim/io/scene_file.h"
#include "scene_builder.h"
#include "simulation_test_helpers.h"

namespace dc = deformable_sim::core;
using deformable_sim::test::boxMeshSimulation;
using deformable_sim::test::defaultSimulation;

namespace {

void expectNetWrench(const std::vector<Eigen::Vector3d>& points,
                     const std::vector<Eigen::Vector3d>& forces, const Eigen::Vector3d& point,
                     const Eigen::Vector3d& force, const Eigen::Vector3d& torque) {
  Eigen::Vector3d net_force = Eigen::Vector3d::Zero(), net_torque = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < points.size(); ++i) {
    net_force += forces[i];
    net_torque += (points[i] - point).cross(forces[i]);
  }
  EXPECT_LT((net_force - force).norm(), 1e-12 * (1 + force.norm()));
  EXPECT_LT((net_torque - torque).norm(), 1e-12 * (1 + torque.norm() + force.norm()));
}

}  // namespace

TEST(Wrench, NetForceAndTorqueAboutAnyPointAreExact) {
  const std::vector<Eigen::Vector3d> points{{0, 0, 0}, {1, 0, 0}, {0, 2, 0}, {0.3, 0.1, 0.7}};
  const std::vector<double> weights{1.0, 2.0, 0.5, 3.0};
  const Eigen::Vector3d force(1, -2, 3), torque(0.5, 0.2, -1), point(2, -1, 4);
  std::vector<Eigen::Vector3d> forces;
  dc::distributeWrench(points, weights, force, torque, point, forces);
  ASSERT_EQ(forces.size(), points.size());
  expectNetWrench(points, forces, point, force, torque);
}

TEST(Wrench, CollinearNodesCarryBendingButNotTwist) {
  const std::vector<Eigen::Vector3d> line{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  const std::vector<double> weights{1, 1, 1};
  std::vector<Eigen::Vector3d> forces;
  // A torque about z (bending the line) is fine.
  dc::distributeWrench(line, weights, {0, 0, 1}, {0, 0, 2}, {1, 0, 0}, forces);
  expectNetWrench(line, forces, {1, 0, 0}, {0, 0, 1}, {0, 0, 2});
  // A twist about the line is refused, not dropped.
  EXPECT_THROW(dc::distributeWrench(line, weights, {0, 0, 0}, {1, 0, 0}, {1, 0, 0}, forces),
               std::invalid_argument);
  // One node: a force is fine, a torque is not.
  dc::distributeWrench({{1, 2, 3}}, {1.0}, {0, 0, -1}, {0, 0, 0}, {1, 2, 3}, forces);
  EXPECT_EQ(forces[0], Eigen::Vector3d(0, 0, -1));
  EXPECT_THROW(dc::distributeWrench({{1, 2, 3}}, {1.0}, {0, 0, 0}, {0, 1, 0}, {1, 2, 3}, forces),
               std::invalid_argument);
}

TEST(RigidFrame, RecoversARigidMotionAndIsIdentityAtRest) {
  dc::Simulation sim = defaultSimulation();
  const dc::Body& body = sim.bodies()[0];
  const dc::RigidFrame rest =
      dc::bestFitFrame(body.positions(), body.restPositions(), body.nodalMasses());
  EXPECT_TRUE(rest.rotation.isApprox(Eigen::Matrix3d::Identity(), 1e-12));
  EXPECT_TRUE(rest.origin.isApprox(Eigen::Vector3d(0.25, 0, 0), 1e-12));
  const Eigen::Matrix3d q =
      Eigen::AngleAxisd(2.5, Eigen::Vector3d(1, 2, -1).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(0.3, -1, 2);
  Eigen::VectorXd moved = body.restPositions();
  for (int i = 0; i < body.numNodes(); ++i) {
    moved.segment<3>(3 * i) =
        q * (body.restPositions().segment<3>(3 * i) - rest.origin) + rest.origin + t;
  }
  const dc::RigidFrame frame = dc::bestFitFrame(moved, body.restPositions(), body.nodalMasses());
  EXPECT_TRUE(frame.rotation.isApprox(q, 1e-12));
  EXPECT_TRUE(frame.origin.isApprox(rest.origin + t, 1e-12));
}

TEST(Commands, GroupWrenchIsExactAndAZeroWrenchClearsIt) {
  dc::Simulation sim = defaultSimulation();
  dc::CommandProcessor commands(sim);
  dc::Body& body = sim.bodies()[0];
  const Eigen::VectorXd scene_forces = body.externalForces();
  dc::WrenchCommand push;
  push.source = "beam/tip";
  push.body = "beam";
  push.nodes.group = "tip";
  push.force = {0, 0.5, -2};
  push.torque = {0.1, 0, 0.05};
  EXPECT_EQ(commands.apply(push), 25);  // the tip face of a 16 x 4 x 4 box: 5 x 5 nodes
  const dc::ActiveWrench& active = commands.activeWrenches().at("beam/tip");
  std::vector<Eigen::Vector3d> points, forces;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double mass = 0.0;
  for (int i : active.nodes) {
    points.emplace_back(body.positions().segment<3>(3 * i));
    forces.emplace_back(body.externalForces().segment<3>(3 * i) - scene_forces.segment<3>(3 * i));
    centroid += body.nodalMasses()[i] * points.back();
    mass += body.nodalMasses()[i];
  }
  // About the group's mass centroid, on the tip face.
  EXPECT_TRUE(active.point.isApprox(centroid / mass, 1e-12));
  EXPECT_NEAR(active.point.x(), 0.5, 1e-12);
  expectNetWrench(points, forces, active.point, push.force, push.torque);
  // Replaced, not added.
  push.force = {0, 0, -1};
  push.torque.setZero();
  commands.apply(push);
  EXPECT_NEAR((body.externalForces() - scene_forces).sum(), -1.0, 1e-12);
  push.force.setZero();
  EXPECT_EQ(commands.apply(push), 0);
  EXPECT_TRUE(commands.activeWrenches().empty());
  EXPECT_EQ(body.externalForces(), scene_forces);
}

TEST(Commands, BadCommandsAreRefusedNamingTheProblemAndChangeNothing) {
  dc::Simulation sim = defaultSimulation();
  dc::CommandProcessor commands(sim);
  dc::Body& body = sim.bodies()[0];
  const Eigen::VectorXd forces = body.externalForces();
  const int constrained = numConstrained(body);
  auto expectRefused = [&](auto command, const std::string& words) {
    try {
      commands.apply(command);
      ADD_FAILURE() << "accepted a command that should be refused for: " << words;
    } catch (const dc::CommandError& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
    EXPECT_EQ(body.externalForces(), forces);
    EXPECT_EQ(numConstrained(body), constrained);
    EXPECT_TRUE(commands.activeWrenches().empty());
  };
  dc::WrenchCommand wrench;
  wrench.source = "test";
  wrench.nodes.group = "tip";
  wrench.force = {0, 0, std::nan("")};
  expectRefused(wrench, "NaN");
  wrench.force = {0, 0, 1e9};
  expectRefused(wrench, "exceeds the limits");
  wrench.force = {0, 0, 1};
  wrench.body = "sponge";
  expectRefused(wrench, "unknown body 'sponge' (bodies: 'beam')");
  wrench.body = "beam";
  wrench.nodes.group = "middle";
  expectRefused(wrench, "has no group 'middle' (groups: tip)");
  wrench.nodes.group.clear();
  wrench.nodes.node_numbers = {1, 99999};
  expectRefused(wrench, "99999");
  // A zero wrench that has nothing to clear is checked like any other.
  wrench.force.setZero();
  expectRefused(wrench, "99999");
  wrench.nodes.node_numbers.clear();
  expectRefused(wrench, "exactly one of");
  wrench.body = "sponge";
  wrench.nodes.group = "tip";
  expectRefused(wrench, "unknown body 'sponge'");
  wrench.body = "beam";
  EXPECT_EQ(commands.apply(wrench), 0);  // a valid target: nothing to clear, nothing changes
  dc::FixCommand fix;
  fix.body = "beam";
  fix.nodes.sphere = dc::Sphere{{5, 5, 5}, 0.1};
  expectRefused(fix, "contains no node");
  fix.nodes.sphere = dc::Sphere{{0.5, 0, 0}, -1.0};
  expectRefused(fix, "radius");
  fix.nodes.sphere.reset();
  fix.nodes.node_numbers = {17, 34};
  fix.targets = {{0.5, 0, 0}};
  expectRefused(fix, "1 targets for 2 nodes");
  fix.targets = {{0.5, 0, 0}, {0.5, 0, std::numeric_limits<double>::infinity()}};
  expectRefused(fix, "NaN or infinite");
  fix.targets.clear();
  fix.nodes.node_numbers.clear();
  expectRefused(fix, "exactly one of");
}

TEST(Commands, FixDragAndReleaseNodes) {
  dc::Simulation sim = defaultSimulation();
  dc::CommandProcessor commands(sim);
  dc::Body& body = sim.bodies()[0];
  const int clamped = numConstrained(body);
  dc::FixCommand drag;
  drag.body = "beam";
  drag.nodes.group = "tip";
  drag.translation = Eigen::Vector3d(0, 0, 0.05);
  EXPECT_EQ(commands.apply(drag), 25);
  EXPECT_EQ(numConstrained(body), clamped + 25);
  std::vector<dc::StepReport> reports;
  sim.step(reports);
  for (int i : body.mesh().groups.at("tip")) {
    EXPECT_NEAR(body.positions()[3 * i + 2] - body.restPositions()[3 * i + 2], 0.05, 1e-12);
  }
  dc::FixCommand release;
  release.body = "beam";
  release.nodes.group = "tip";
  release.fix = false;
  EXPECT_EQ(commands.apply(release), 25);
  EXPECT_EQ(numConstrained(body), clamped);
}

TEST(DefaultScene, TheShippedSceneFileIsTheBuiltInScene) {
  const dc::SceneSpec built_in = dc::defaultScene();
  const dc::SceneSpec file = deformable_sim::io::readSceneFile(
      std::string(DEFORMABLE_SIM_SOURCE_DIR) + "/config/scenes/cantilever.yaml");
  EXPECT_EQ(file.dt, built_in.dt);
  EXPECT_EQ(*file.effects.gravity, *built_in.effects.gravity);
  EXPECT_EQ(file.effects.warping, built_in.effects.warping);
  EXPECT_EQ(file.effects.damping->mass, built_in.effects.damping->mass);
  EXPECT_EQ(file.effects.damping->stiffness, built_in.effects.damping->stiffness);
  EXPECT_EQ(file.solver.method, built_in.solver.method);
  EXPECT_EQ(file.solver.tolerance, built_in.solver.tolerance);
  EXPECT_EQ(file.solver.max_iterations, built_in.solver.max_iterations);
  ASSERT_EQ(file.bodies.size(), 1u);
  const dc::BodySpec &a = file.bodies[0], &b = built_in.bodies[0];
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.box_mesh->min, b.box_mesh->min);
  EXPECT_EQ(a.box_mesh->max, b.box_mesh->max);
  EXPECT_EQ(a.box_mesh->cells, b.box_mesh->cells);
  EXPECT_EQ(a.material.youngs_modulus, b.material.youngs_modulus);
  EXPECT_EQ(a.material.poisson_ratio, b.material.poisson_ratio);
  EXPECT_EQ(a.material.density, b.material.density);
  EXPECT_EQ(a.wrench_radius, b.wrench_radius);
  // Same selections: compare what they select on the same mesh.
  const dc::Mesh mesh = dc::makeBoxMesh(b.box_mesh->min, b.box_mesh->max, b.box_mesh->cells);
  EXPECT_EQ(dc::selectNodes(mesh, a.fixed.at(0)), dc::selectNodes(mesh, b.fixed.at(0)));
  EXPECT_EQ(dc::selectNodes(mesh, a.groups.at("tip")), dc::selectNodes(mesh, b.groups.at("tip")));
}

namespace {

// A soft block, 0.1 m on a side, hanging from nothing yet: no clamp, gravity on, heavy damping;
// with `floor`, standing on one.
dc::Simulation makeBlock(bool floor = false) {
  dc::SceneSpec spec;
  spec.dt = 0.01;
  spec.effects.gravity = Eigen::Vector3d(0, 0, -9.81);
  spec.effects.warping = true;
  spec.effects.damping = dc::RayleighDamping{20.0, 0.0};
  spec.solver.tolerance = 1e-12;
  dc::BodySpec block;
  block.name = "block";
  block.box_mesh = dc::BoxMeshSpec{{0, 0, 0}, {0.1, 0.1, 0.1}, {4, 4, 4}};
  block.material = {5.0e4, 0.3, 200.0};
  spec.bodies.push_back(block);
  if (floor) {
    spec.contact = dc::ContactSettings{0.5, false, false};
    spec.obstacles.push_back(deformable_sim::test::floorBox({1, 1, 0.1}, ""));
  }
  return boxMeshSimulation(spec);
}

dc::GraspCommand graspTopCorner(const Eigen::Isometry3d& frame) {
  dc::GraspCommand grasp;
  grasp.name = "hand";
  grasp.nodes.box = dc::Box{{-0.001, -0.001, 0.074}, {0.026, 0.026, 0.101}};
  grasp.frame = frame;
  return grasp;
}

}  // namespace

TEST(Grasps, NodesFollowTheFrameExactlyEvenWhenItMovesFast) {
  dc::Simulation sim = makeBlock();
  dc::CommandProcessor commands(sim);
  Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();
  frame.translation() << 0.0, 0.0, 0.1;
  EXPECT_EQ(commands.apply(graspTopCorner(frame)), 2 * 2 * 2);
  const dc::ActiveGrasp& grasp = commands.grasps().at("hand");
  std::vector<dc::StepReport> reports;
  for (int s = 1; s <= 50; ++s) {
    // 2 m/s and 10 rad/s: far more than an element per step.
    frame.translation() << 0.02 * s, 0.0, 0.1;
    frame.linear() = Eigen::AngleAxisd(0.1 * s, Eigen::Vector3d::UnitY()).toRotationMatrix();
    commands.moveGrasp("hand", frame);
    sim.step(reports);
    const dc::Body& body = sim.bodies()[0];
    for (size_t k = 0; k < grasp.nodes.size(); ++k) {
      ASSERT_LT((body.positions().segment<3>(3 * grasp.nodes[k]) - frame * grasp.local[k]).norm(),
                1e-9);
    }
    ASSERT_TRUE(body.positions().allFinite());
  }
}

TEST(Grasps, HangingBodyReactionIsItsWeightAboutItsCentreOfMass) {
  dc::Simulation sim = makeBlock();
  dc::CommandProcessor commands(sim);
  Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();
  frame.translation() << 0.01, 0.01, 0.09;
  commands.apply(graspTopCorner(frame));
  std::vector<dc::StepReport> reports;
  for (int s = 0; s < 1500; ++s) sim.step(reports);
  const dc::Body& body = sim.bodies()[0];
  double mass = 0.0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (int i = 0; i < body.numNodes(); ++i) {
    mass += body.nodalMasses()[i];
    centre += body.nodalMasses()[i] * body.positions().segment<3>(3 * i);
  }
  centre /= mass;
  EXPECT_NEAR(mass, 200.0 * 1e-3, 1e-12);
  const Eigen::Vector3d weight(0, 0, -9.81 * mass);
  EXPECT_LT(body.velocities().lpNorm<Eigen::Infinity>(), 1e-9);
  const dc::Wrench reaction = commands.graspReaction("hand");
  EXPECT_LT((reaction.force + weight).norm(), 1e-6 * weight.norm()) << reaction.force.transpose();
  // At rest the grasp's torque cancels the weight's about the frame origin.
  const Eigen::Vector3d expected = -(centre - frame.translation()).cross(weight);
  EXPECT_LT((reaction.torque - expected).norm(), 1e-6 * weight.norm() * 0.1)
      << reaction.torque.transpose() << " vs " << expected.transpose();
  EXPECT_GT(expected.norm(), 0.01);  // the corner grasp holds the block off-centre
  // Released, the body keeps its place and falls from there.
  const Eigen::VectorXd before = body.positions();
  EXPECT_TRUE(commands.releaseGrasp("hand"));
  EXPECT_EQ(numConstrained(body), 0);
  EXPECT_EQ(body.positions(), before);
  sim.step(reports);
  // Internal forces cancel: from rest the centre of mass falls by h^2 g / (1 + h alpha) in one
  // implicit step with mass damping alpha.
  Eigen::Vector3d moved = Eigen::Vector3d::Zero();
  for (int i = 0; i < body.numNodes(); ++i) {
    moved += body.nodalMasses()[i] * (body.positions() - before).segment<3>(3 * i) / mass;
  }
  const double h = 0.01, alpha = 20.0;
  EXPECT_NEAR(moved.z(), -h * h * 9.81 / (1 + h * alpha), 1e-9);
  EXPECT_NEAR(moved.head<2>().norm(), 0.0, 1e-12);
}

// ~grasps/<name>/wrench and the tf frame <name>/object: what the hand feels and where the object
// is, both in the hand's frame.
TEST(Grasps, TheReactionAndTheObjectAreSeenFromTheHand) {
  dc::Simulation sim = makeBlock();
  dc::CommandProcessor commands(sim);
  Eigen::Isometry3d hand = Eigen::Isometry3d::Identity();
  hand.translation() << 0.01, 0.01, 0.09;
  hand.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  commands.apply(graspTopCorner(hand));
  const Eigen::Translation3d centroid(0.05, 0.05, 0.05);  // the object's frame: at its centroid
  EXPECT_TRUE(commands.objectInGrasp("hand").isApprox(hand.inverse() * centroid, 1e-12));
  dc::Body& body = sim.bodies()[0];
  const Eigen::Vector3d shift(0.0, 0.0, -0.02);  // the object slipped 2 cm down in the hand
  body.setState(body.restPositions() + shift.replicate(body.numNodes(), 1),
                Eigen::VectorXd::Zero(3 * body.numNodes()));
  const Eigen::Isometry3d slipped = hand.inverse() * Eigen::Translation3d(shift) * centroid;
  EXPECT_TRUE(commands.objectInGrasp("hand").isApprox(slipped, 1e-12));

  // A force of 1 N down at x = 1 m: about the origin of a hand turned 90 degrees about z, whose
  // x axis is the world's y, the torque is +1 N m about the world's y, its own x.
  const dc::Wrench load{{0, 0, -1}, {0, 0, 0}, {1, 0, 0}};
  Eigen::Isometry3d sensor = Eigen::Isometry3d::Identity();
  sensor.linear() = hand.linear();
  const dc::Wrench seen = dc::seenFrom(load, sensor);
  EXPECT_TRUE(seen.force.isApprox(Eigen::Vector3d(0, 0, -1), 1e-12));
  EXPECT_TRUE(seen.torque.isApprox(Eigen::Vector3d(1, 0, 0), 1e-12)) << seen.torque.transpose();
  sensor.translation() << 1, 0, 5;  // on the force's line: no torque
  EXPECT_LT(dc::seenFrom(load, sensor).torque.norm(), 1e-12);
}

// The node's log line and ~stats of a body: what it is made of, what it runs, what acts on it.
TEST(BodyActivity, SaysWhatABodyIsAndWhatActsOnIt) {
  dc::Simulation sim = makeBlock(true);
  dc::CommandProcessor commands(sim);
  // 4 x 4 x 4 cubes of six tetrahedra; reactions are on unless a scene turns them off.
  EXPECT_EQ(dc::bodySummary(sim, 0),
            "body 'block' (fem): 125 nodes, 384 tetrahedra, 0 other elements, 0 fixed; effects: "
            "warping, gravity, damping, reactions, contact");
  commands.apply(graspTopCorner(Eigen::Isometry3d::Identity()));
  dc::WrenchCommand push;
  push.source = "push";
  push.nodes.whole_body = true;
  push.force = Eigen::Vector3d(1, 0, 0);
  commands.apply(push);
  EXPECT_EQ(dc::graspedNodes(commands, 0), 8);
  EXPECT_EQ(dc::appliedWrenches(commands, 0), 1);
  EXPECT_NE(dc::bodySummary(sim, 0).find(", 8 fixed;"), std::string::npos);  // grasped: held
}

TEST(Grasps, RefusesEmptyRegionsAndNodesHeldElsewhere) {
  dc::Simulation sim = makeBlock();
  dc::CommandProcessor commands(sim);
  dc::GraspCommand grasp = graspTopCorner(Eigen::Isometry3d::Identity());
  grasp.nodes.box = dc::Box{{1, 1, 1}, {2, 2, 2}};
  EXPECT_THROW(
      {
        try {
          commands.apply(grasp);
        } catch (const dc::CommandError& e) {
          EXPECT_STREQ(e.what(), "grasp 'hand': body 'block': the box contains no node");
          throw;
        }
      },
      dc::CommandError);
  commands.apply(graspTopCorner(Eigen::Isometry3d::Identity()));
  dc::GraspCommand other = graspTopCorner(Eigen::Isometry3d::Identity());
  other.name = "other";
  try {
    commands.apply(other);
    ADD_FAILURE() << "a second grasp took nodes the first holds";
  } catch (const dc::CommandError& e) {
    EXPECT_NE(std::string(e.what()).find("is already held by grasp 'hand'"), std::string::npos);
  }
  dc::FixCommand release;
  release.fix = false;
  release.nodes.box = dc::Box{{-1, -1, -1}, {2, 2, 2}};
  try {
    commands.apply(release);
    ADD_FAILURE() << "released grasped nodes through fixed_nodes";
  } catch (const dc::CommandError& e) {
    EXPECT_NE(std::string(e.what()).find("release the grasp instead"), std::string::npos);
  }
  EXPECT_EQ(numConstrained(sim.bodies()[0]), 8);
}

// A frame that jumps across the world (a tf pose of 1e300 m) is refused like a fixed-node
// target that far, and the grasp holds where it was.
TEST(Grasps, AFrameThatJumpsFartherThanTheTargetLimitIsRefused) {
  dc::Simulation sim = makeBlock(true);
  dc::CommandProcessor commands(sim);
  commands.apply(graspTopCorner(Eigen::Isometry3d::Identity()));
  Eigen::Isometry3d far = Eigen::Isometry3d::Identity();
  far.translation() << 0.0, 0.0, 1e300;
  try {
    commands.moveGrasp("hand", far);
    ADD_FAILURE() << "a grasp was moved 1e300 m";
  } catch (const dc::CommandError& e) {
    EXPECT_NE(std::string(e.what()).find("grasp 'hand': the frame would take node"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("more than 10.0"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(commands.grasps().at("hand").frame.isApprox(Eigen::Isometry3d::Identity()));
  std::vector<dc::StepReport> reports;
  sim.step(reports);
  EXPECT_FALSE(reports[0].recovered);
  EXPECT_TRUE(sim.bodies()[0].stateIsFinite());
}

// With no limit on targets, seven of a one-cell block's eight nodes sent 1e300 m away, a floor
// put over the eighth (a fuzz finding): every step the watchdog undoes ends finite, whether the
// body's own step or the contact after it overflowed.
TEST(Watchdog, KeepsABodyThrownFarByAnUnlimitedGraspFinite) {
  dc::SceneSpec spec;  // the fuzz scene's block, on its floor
  spec.dt = 0.01;
  spec.effects.gravity = Eigen::Vector3d(0, 0, -9.81);
  spec.effects.warping = true;
  spec.effects.damping = dc::RayleighDamping{1.0, 0.002};
  spec.contact = dc::ContactSettings{0.5, false, false};
  dc::PlacedShape ground;
  ground.name = "floor";
  ground.shape.size = Eigen::Vector3d(2, 2, 0.1);
  ground.pose.translation() = Eigen::Vector3d(0, 0, -0.1);
  spec.obstacles.push_back(ground);
  dc::BodySpec block;
  block.name = "block";
  block.box_mesh = dc::BoxMeshSpec{{0.3, 0, 0}, {0.35, 0.05, 0.05}, {1, 1, 1}};
  block.material = {3.0e4, 0.3, 150.0};
  spec.bodies.push_back(block);
  dc::CommandLimits unlimited;
  unlimited.max_target_distance = std::numeric_limits<double>::infinity();
  dc::Session session(spec, deformable_sim::io::readMeshes(spec, nullptr), unlimited);
  dc::GraspCommand grasp;
  grasp.name = "hand";
  grasp.nodes.sphere = dc::Sphere{{0.328, 0.031, 0.031}, 0.05};  // all but the node at (0.3, 0, 0)
  grasp.frame.translation() << 0.328, 0.031, 0.031;
  EXPECT_EQ(session.apply(grasp), 7);
  std::vector<dc::StepReport> reports;
  session.step(reports);
  Eigen::Isometry3d far = grasp.frame;
  far.translation().z() = 1e300;
  session.apply(dc::MoveGraspCommand{"hand", far});
  dc::PlacedShape floor;
  floor.name = "floor";
  floor.shape.size = Eigen::Vector3d(1, 1, 0.05);
  session.apply(dc::SetObstaclesCommand{{floor}});
  for (int s = 1; s <= 3; ++s) {
    session.step(reports);
    EXPECT_TRUE(session.simulation().bodies()[0].stateIsFinite()) << "step " << s;
  }
  EXPECT_TRUE(reports[0].recovered);
  EXPECT_GE(session.simulation().recoveries(0), 1);
}

TEST(Commands, SphereWithANonFiniteCentreIsRefusedInAMultiBodyScene) {
  // With several bodies and none named, the sphere's centre picks the body: a NaN picks none.
  dc::SceneSpec spec = dc::defaultScene();
  spec.bodies.push_back(spec.bodies[0]);
  spec.bodies[1].name = "other";
  dc::Simulation sim = boxMeshSimulation(spec);
  dc::CommandProcessor commands(sim);
  dc::FixCommand fix;
  fix.nodes.sphere = dc::Sphere{Eigen::Vector3d(std::nan(""), 0, 0), 0.1};
  try {
    commands.apply(fix);
    FAIL() << "accepted";
  } catch (const dc::CommandError& e) {
    EXPECT_STREQ(e.what(), "the sphere's centre has a non-finite coordinate");
  }
  EXPECT_EQ(numConstrained(sim.bodies()[0]), 25);
  EXPECT_EQ(numConstrained(sim.bodies()[1]), 25);
  fix.nodes.sphere->center = Eigen::Vector3d(1e300, 0, 0);  // every distance overflows
  EXPECT_THROW(commands.apply(fix), dc::CommandError);

  // The centre is taken in the sphere's frame: 2 m along y, the second body's tip is nearest.
  sim.bodies()[1].setState(sim.bodies()[1].positions() +
                               Eigen::Vector3d(0, 2, 0).replicate(sim.bodies()[1].numNodes(), 1),
                           sim.bodies()[1].velocities());
  fix.nodes.sphere = dc::Sphere{Eigen::Vector3d(0.5, 0, 0), 0.01};
  fix.nodes.region_pose = Eigen::Isometry3d(Eigen::Translation3d(0, 2, 0));
  EXPECT_EQ(commands.apply(fix), 1);
  EXPECT_EQ(numConstrained(sim.bodies()[1]), 26);
  EXPECT_EQ(numConstrained(sim.bodies()[0]), 25);
}
