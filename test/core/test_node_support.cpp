// The ROS-free pieces of the node that act on a session: body frames, the wrench bounds a body can
// take, wrenches in far frames, live tuning and grasps following their frames. The pieces that
// stand alone have a test named after their header (test_tick_status.cpp and the like).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "deformable_sim/core/driver/body_frame_lookup.h"
#include "deformable_sim/core/driver/grasp_follower.h"
#include "deformable_sim/core/session/default_scene.h"
#include "deformable_sim/core/session/live_settings.h"
#include "deformable_sim/io/scene_file.h"

namespace deformable_sim::core {
namespace {

Session defaultSession(CommandLimits limits = {}) {
  const SceneSpec scene = defaultScene();
  return Session(scene, io::readMeshes(scene, nullptr), limits);
}

std::string refusal(Session& session, const SessionCommand& command) {
  try {
    session.apply(command);
  } catch (const CommandError& e) {
    return e.what();
  }
  return "";
}

WrenchCommand tipPush(double force_z, double torque_x = 0.0) {
  WrenchCommand push;
  push.source = "test";
  push.body = "beam";
  push.nodes.group = "tip";
  push.force = {0.0, 0.0, force_z};
  push.torque = {torque_x, 0.0, 0.0};
  return push;
}

TEST(BodyFrames, NameBodiesAndGroupsAndNothingElse) {
  Session session = defaultSession();
  const BodyList& bodies = session.simulation().bodies();
  const BodyFrame beam = findBodyFrame(bodies, "sim/", "sim/beam");
  EXPECT_EQ(beam.body, 0);
  EXPECT_TRUE(beam.group.empty());
  EXPECT_NEAR(beam.pose.translation().x(), 0.25, 1e-12);  // the centroid of the 0.5 m beam
  const BodyFrame tip = findBodyFrame(bodies, "sim/", "sim/beam/tip");
  EXPECT_EQ(tip.group, "tip");
  EXPECT_NEAR(tip.pose.translation().x(), 0.5, 1e-12);
  EXPECT_EQ(findBodyFrame(bodies, "sim/", "beam").body, -1);  // without the prefix: not ours
  EXPECT_EQ(findBodyFrame(bodies, "sim/", "gripper").body, -1);
  try {
    findBodyFrame(bodies, "sim/", "sim/beam/middle");
    FAIL() << "an unknown group was accepted";
  } catch (const CommandError& e) {
    EXPECT_NE(std::string(e.what()).find("no group 'middle' (groups: tip)"), std::string::npos)
        << e.what();
  }
}

// What tf gets is what a message may name: every frame broadcast resolves to itself.
TEST(BodyFrames, EveryFrameBroadcastResolvesToTheSamePose) {
  Session session = defaultSession();
  const BodyList& bodies = session.simulation().bodies();
  const auto frames = allBodyFrames(bodies, "sim/");
  ASSERT_EQ(frames.size(), 2u);  // the beam and its group "tip"
  EXPECT_EQ(frames[0].first, "sim/beam");
  EXPECT_EQ(frames[1].first, "sim/beam/tip");
  for (const auto& [name, pose] : frames) {
    EXPECT_TRUE(findBodyFrame(bodies, "sim/", name).pose.isApprox(pose, 1e-15)) << name;
  }
}

TEST(WrenchNearPoint, ActsOnTheNearestBodyWithinItsRadius) {
  Session session = defaultSession();
  const WrenchCommand near = wrenchNearPoint(session.simulation(), "finger", {0.52, 0.0, 0.0},
                                             {0.0, 0.0, -1.0}, Eigen::Vector3d::Zero());
  EXPECT_EQ(near.body, "beam");
  EXPECT_EQ(near.source, "finger");
  ASSERT_TRUE(near.nodes.sphere.has_value());
  EXPECT_DOUBLE_EQ(near.nodes.sphere->radius, 0.05);
  EXPECT_GT(session.apply(near), 0);
}

TEST(WrenchNearPoint, AFarFrameIsRefusedWithTheFrameTheBodyItsDistanceAndRadius) {
  Session session = defaultSession();
  try {
    wrenchNearPoint(session.simulation(), "far_frame", {3.5, 0.0, 0.0}, {0.0, 0.0, -1.0},
                    Eigen::Vector3d::Zero());
    FAIL() << "a frame 3 m from the body was accepted";
  } catch (const CommandError& e) {
    const std::string what = e.what();
    for (const char* word : {"far_frame", "'beam'", "3 m", "wrench_radius 0.05 m"}) {
      EXPECT_NE(what.find(word), std::string::npos) << word << " missing from: " << what;
    }
  }
}

TEST(WrenchInFrame, TurnsTheWrenchIntoTheWorldAndActsAtTheFramesOrigin) {
  Session session = defaultSession();
  BodyFrame tip = findBodyFrame(session.simulation().bodies(), "", "beam/tip");
  tip.pose.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const WrenchCommand command =
      wrenchInFrame(session.simulation(), "beam/tip", tip, {1.0, 0.0, 0.0}, {0.0, 0.0, 0.0});
  EXPECT_EQ(command.body, "beam");
  EXPECT_EQ(command.nodes.group, "tip");
  EXPECT_FALSE(command.nodes.whole_body);
  EXPECT_TRUE(command.force.isApprox(Eigen::Vector3d(0.0, 1.0, 0.0), 1e-15));  // x turned to y
  EXPECT_NEAR(command.point->x(), 0.5, 1e-12);
  BodyFrame elsewhere;  // a tf frame 2 cm beyond the tip
  elsewhere.pose.translation() = Eigen::Vector3d(0.52, 0.0, 0.0);
  const WrenchCommand near = wrenchInFrame(session.simulation(), "finger", elsewhere,
                                           {0.0, 0.0, -1.0}, Eigen::Vector3d::Zero());
  EXPECT_TRUE(near.nodes.sphere.has_value());
  EXPECT_EQ(near.source, "finger");
}

TEST(WrenchBounds, DefaultToTenTimesTheBodysWeightAndThatForceTimesItsSize) {
  Session session = defaultSession();
  const Body& beam = session.simulation().bodies()[0];
  const WrenchBounds bounds = wrenchBounds(beam, CommandLimits{});
  const double weight = 0.5 * 0.1 * 0.1 * 100.0 * 9.81;  // 0.5 kg of foam
  EXPECT_NEAR(bounds.force, 10.0 * weight, 1e-9);
  EXPECT_NEAR(bounds.torque, 10.0 * weight * 0.5, 1e-9);  // the beam is 0.5 m long
  const WrenchBounds set = wrenchBounds(beam, CommandLimits{100.0, 3.0, 10.0});
  EXPECT_EQ(set.force, 100.0);
  EXPECT_EQ(set.torque, 3.0);
}

TEST(WrenchBounds, AThrowingPushIsRefusedAndOneTheBodyCanTakeIsApplied) {
  Session session = defaultSession();
  const std::string refused = refusal(session, tipPush(-9000.0));
  EXPECT_NE(refused.find("exceeds the limits of body 'beam'"), std::string::npos) << refused;
  EXPECT_NE(refusal(session, tipPush(0.0, 30.0)), "");  // 30 N m > 24.5 N m
  EXPECT_TRUE(session.commands().activeWrenches().empty());
  EXPECT_EQ(refusal(session, tipPush(-49.0)), "");
  std::vector<StepReport> reports;
  for (int step = 0; step < 200; ++step) {
    session.step(reports);
    ASSERT_EQ(reports[0].inverted_elements, 0) << "at step " << step;
  }
  EXPECT_TRUE(session.simulation().bodies()[0].positions().allFinite());
}

TEST(LiveSettings, ChangeOnlyWhatDiffers) {
  Session session = defaultSession();
  const LiveSettings before = liveSettings(session.simulation().bodies()[0], 100.0);
  EXPECT_EQ(before.youngs_modulus, 1.0e5);
  EXPECT_TRUE(tuneCommands(session.simulation(), before, before, 1).empty());
  LiveSettings after = before;
  after.youngs_modulus = 2.0e5;
  after.rate = 50.0;
  const std::vector<TuneCommand> tunes = tuneCommands(session.simulation(), before, after, 2);
  ASSERT_EQ(tunes.size(), 2u);
  EXPECT_EQ(tunes[0].material->youngs_modulus, 2.0e5);
  EXPECT_EQ(tunes[0].material->poisson_ratio, 0.3);
  EXPECT_FALSE(tunes[0].damping || tunes[0].solver_tolerance || tunes[0].dt);
  EXPECT_DOUBLE_EQ(*tunes[1].dt, 0.01);
}

TEST(LiveSettings, ImpossibleValuesAreRefusedNamingTheParameterNotClamped) {
  Session session = defaultSession();
  const LiveSettings before = liveSettings(session.simulation().bodies()[0], 100.0);
  const auto refusedWith = [&](LiveSettings after) -> std::string {
    try {
      for (const TuneCommand& tune : tuneCommands(session.simulation(), before, after, 1)) {
        session.apply(tune);
      }
    } catch (const CommandError& e) {
      return e.what();
    }
    return "";
  };
  LiveSettings bad = before;
  bad.youngs_modulus = -5.0;
  EXPECT_NE(refusedWith(bad).find("youngs_modulus is -5"), std::string::npos);
  bad = before;
  bad.poisson_ratio = 0.5;
  EXPECT_NE(refusedWith(bad).find("poisson_ratio is 0.5"), std::string::npos);
  bad = before;
  bad.solver_tolerance = -1.0;
  EXPECT_NE(refusedWith(bad).find("tolerance"), std::string::npos);
  for (const double rate : {0.0, 1e-4, 1e9, std::nan("")}) {
    bad = before;
    bad.rate = rate;  // a period no timer keeps
    EXPECT_NE(refusedWith(bad).find("rate"), std::string::npos) << rate;
  }
  bad = before;
  bad.body = "sponge";
  EXPECT_NE(refusedWith(bad).find("no body named 'sponge'"), std::string::npos);
  const Body& beam = session.simulation().bodies()[0];
  EXPECT_EQ(beam.settings().material.youngs_modulus, 1.0e5);  // nothing changed
  EXPECT_EQ(beam.settings().material.poisson_ratio, 0.3);
  EXPECT_EQ(beam.settings().solver.tolerance, 1.0e-5);
  EXPECT_EQ(session.simulation().dt(), 0.01);
}

TEST(GraspFollower, MovesEachGraspEvenlyToItsFramesPoseAndHoldsALostOne) {
  Session session = defaultSession();
  GraspCommand grasp;
  grasp.name = "hand";
  grasp.body = "beam";
  grasp.nodes.group = "tip";
  grasp.frame.translation() = Eigen::Vector3d(0.5, 0.0, 0.0);
  session.apply(grasp);
  grasp.name = "other";
  grasp.nodes.group.clear();
  grasp.nodes.sphere = Sphere{{0.25, 0.0, 0.0}, 0.03};
  session.apply(grasp);
  GraspFollower follower;
  follower.follow("hand", "gripper");
  follower.follow("other", "lost_frame");
  const auto pose = [](const std::string& frame) -> std::optional<Eigen::Isometry3d> {
    if (frame != "gripper") return std::nullopt;
    Eigen::Isometry3d to = Eigen::Isometry3d::Identity();
    to.translation() = Eigen::Vector3d(0.5, 0.0, 0.4);
    return to;
  };
  EXPECT_EQ(follower.plan(session.commands(), pose), std::vector<std::string>{"other"});
  const std::vector<MoveGraspCommand> first = follower.moves(1, 4);
  ASSERT_EQ(first.size(), 2u);
  EXPECT_EQ(first[0].name, "hand");
  EXPECT_NEAR(first[0].frame.translation().z(), 0.1, 1e-15);
  EXPECT_NEAR(first[1].frame.translation().x(), 0.5, 1e-15);  // held where it was
  EXPECT_EQ(follower.moves(4, 4)[0].frame.translation().z(), 0.4);
  follower.forget("other");
  EXPECT_EQ(follower.moves(4, 4).size(), 1u);
}

}  // namespace
}  // namespace deformable_sim::core
