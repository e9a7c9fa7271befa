// The ROS-free pieces the node is built from: body frames, the wrench bounds a body can take,
// wrenches in far frames, live tuning and lapsing wrenches (output schedules:
// test_periodic_schedule.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "deformable_sim/core/driver/body_frame_lookup.h"
#include "deformable_sim/core/driver/grasp_follower.h"
#include "deformable_sim/core/driver/linked_obstacles.h"
#include "deformable_sim/core/driver/once_per_stamp.h"
#include "deformable_sim/core/driver/pose_interpolation.h"
#include "deformable_sim/core/driver/real_time_factor.h"
#include "deformable_sim/core/driver/refusal_log.h"
#include "deformable_sim/core/driver/slow_tick_watch.h"
#include "deformable_sim/core/driver/tick_status.h"
#include "deformable_sim/core/driver/wrench_timeouts.h"
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
  const std::vector<Body>& bodies = session.simulation().bodies();
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
  const std::vector<Body>& bodies = session.simulation().bodies();
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

TEST(OncePerStamp, LetsEachStampThroughOnceAndANewTimelineStartAgain) {
  OncePerStamp stamps;
  EXPECT_TRUE(stamps.accept(5'000'000'000));
  EXPECT_FALSE(stamps.accept(5'000'000'000));  // the timer fired twice at one time
  EXPECT_FALSE(stamps.accept(4'990'000'000));
  EXPECT_TRUE(stamps.accept(5'010'000'000));
  EXPECT_TRUE(stamps.accept(1'000'000'000));  // a looped bag: seconds back
  EXPECT_FALSE(stamps.accept(1'000'000'000));
}

TEST(RealTimeFactor, IsSimulatedTimeOverClockTimeOfTheLastSecond) {
  RealTimeFactor factor;
  EXPECT_EQ(factor.value(), 0.0);
  for (int k = 0; k <= 300; ++k) factor.sample(0.01 * k, 0.005 * k);
  EXPECT_NEAR(factor.value(), 0.5, 1e-9);
  factor.sample(1.0, 2.0);  // the clock went back: start again
  EXPECT_EQ(factor.value(), 0.0);
}

TEST(WrenchTimeouts, ASilentSourceLapsesAndAZeroWrenchIsForgotten) {
  WrenchTimeouts timeouts(0.5);
  timeouts.heard("a", 1.0, false);
  timeouts.heard("b", 1.2, false);
  timeouts.heard("b", 1.3, true);  // b cleared its own wrench
  EXPECT_TRUE(timeouts.expire(1.4).empty());
  EXPECT_EQ(timeouts.expire(1.6), std::vector<std::string>{"a"});
  EXPECT_TRUE(timeouts.expire(9.0).empty());
  WrenchTimeouts never;
  never.heard("a", 0.0, false);
  EXPECT_TRUE(never.expire(1e9).empty());
}

TEST(RefusalLog, CountsEveryRefusalAndWarnsOnceASecondPerTopic) {
  RefusalLog log;
  EXPECT_EQ(log.refuse("~wrench", "NaN", 10.0), "~wrench: NaN (message dropped)");
  EXPECT_EQ(log.refuse("~wrench", "NaN", 10.2), "");
  EXPECT_EQ(log.refuse("~wrench", "huge", 10.4), "");
  EXPECT_NE(log.refuse("~grasp", "unknown frame", 10.5), "");  // another topic: not throttled
  EXPECT_EQ(log.refuse("~wrench", "NaN", 11.1),
            "~wrench: NaN (message dropped; 2 more dropped on ~wrench since the last warning)");
  EXPECT_EQ(log.count(), 5u);
  EXPECT_EQ(log.last(), "~wrench: NaN");
}

TEST(Health, WarnsOfRecoveriesMissedTolerancesAndLostRealTimeInThatOrder) {
  TickStatus status;
  status.reports.resize(1);
  status.reports[0].solve.converged = true;
  status.reports[0].inverted_elements = 3;
  status.real_time_factor = 0.03;  // but not for long yet
  status.steps = 1;
  status.step_time_s = 0.29;
  status.reports[0].times.body_contact = 0.28;
  Health h = health(status);
  EXPECT_TRUE(h.ok);
  EXPECT_EQ(h.summary, "running");
  EXPECT_EQ(h.inverted_elements, 3);
  status.slow = true;
  EXPECT_EQ(
      health(status).summary,
      "cannot keep real time (0.03 x real time): contact between bodies 280 of 290 ms a step");
  status.paused = true;
  EXPECT_EQ(health(status).summary, "paused");
  status.reports[0].solve.converged = false;
  EXPECT_EQ(health(status).summary, "a solve did not reach its tolerance");
  status.recent_recovery = true;
  h = health(status);
  EXPECT_FALSE(h.ok);
  EXPECT_EQ(h.summary, "the watchdog undid a step that left a non-finite value");
}

// The costliest part of the last step, summed over the bodies, against the tick's time a step.
TEST(Health, NamesTheCostliestPartOfAStep) {
  TickStatus status;
  status.steps = 10;
  status.step_time_s = 0.05;  // 5 ms a step
  status.reports.resize(2);
  status.reports[0].times.rotations = 0.0005;
  status.reports[0].times.assembly = 0.0010;
  status.reports[1].times.assembly = 0.0010;
  status.reports[0].times.solve = 0.0020;
  status.reports[1].times.obstacle_contact = 0.0001;
  EXPECT_EQ(costliestPart(status), "elasticity 2.5 of 5 ms a step");
  status.reports[1].times.solve = 0.0010;
  EXPECT_EQ(costliestPart(status), "linear solves 3 of 5 ms a step");
  status.reports[0].times.obstacle_contact = 0.0040;
  EXPECT_EQ(costliestPart(status), "contact with obstacles 4.1 of 5 ms a step");
}

// Slow for 5 s of wall time in a row, not at one slow tick; a pause or a fast tick starts over.
TEST(SlowTickWatch, IsSlowAfterFiveSecondsUnderNineTenthsOfRealTime) {
  SlowTickWatch watch;
  for (double t = 0.0; t < 4.95; t += 0.1) {
    watch.sample(t, 0.5, true);
    ASSERT_FALSE(watch.slow()) << t;
  }
  watch.sample(5.0, 0.5, true);
  EXPECT_TRUE(watch.slow());
  EXPECT_DOUBLE_EQ(watch.slowFor(5.0), 5.0);
  watch.sample(5.1, 0.95, true);  // caught up
  EXPECT_FALSE(watch.slow());
  EXPECT_EQ(watch.slowFor(5.1), 0.0);
  for (double t = 6.0; t < 12.5; t += 1.0) watch.sample(t, 0.5, t != 9.0);
  EXPECT_FALSE(watch.slow());  // the pause at 9 s started the count again
  watch.sample(15.0, 0.5, true);
  EXPECT_TRUE(watch.slow());
  watch.sample(14.0, 0.5, true);  // the clock went back
  EXPECT_FALSE(watch.slow());
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
  EXPECT_EQ(beam.material().youngs_modulus, 1.0e5);  // nothing changed
  EXPECT_EQ(beam.material().poisson_ratio, 0.3);
  EXPECT_EQ(beam.solverSettings().tolerance, 1.0e-5);
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

TEST(LinkedObstacles, PlaceShapesWithTheirFramesAndWaitForEveryFrame) {
  PlacedShape floor;
  floor.name = "floor";
  PlacedShape finger;
  finger.name = "finger";
  finger.pose.translation() = Eigen::Vector3d(0.0, 0.0, 0.1);  // in the link's frame
  LinkedObstacles obstacles({floor});
  obstacles.attach("link", finger);
  std::optional<Eigen::Isometry3d> link;
  const auto pose = [&link](const std::string&) { return link; };
  EXPECT_FALSE(obstacles.place(pose));  // never placed yet: no stepping
  link = Eigen::Isometry3d::Identity();
  link->translation() = Eigen::Vector3d(1.0, 0.0, 0.0);
  std::optional<std::vector<PlacedShape>> placed = obstacles.place(pose);
  ASSERT_TRUE(placed && placed->size() == 2u);
  EXPECT_EQ((*placed)[0].name, "floor");
  EXPECT_TRUE((*placed)[1].pose.translation().isApprox(Eigen::Vector3d(1.0, 0.0, 0.1)));
  link.reset();  // tf lost the link: it stays where it was
  placed = obstacles.place(pose);
  ASSERT_TRUE(placed);
  EXPECT_TRUE((*placed)[1].pose.translation().isApprox(Eigen::Vector3d(1.0, 0.0, 0.1)));
}

TEST(PoseInterpolation, RunsFromOnePoseToTheOther) {
  Eigen::Isometry3d from = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d to = Eigen::Isometry3d::Identity();
  to.translate(Eigen::Vector3d(1.0, 2.0, 3.0));
  to.rotate(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  EXPECT_TRUE(interpolatePose(from, to, 0.0).isApprox(from, 1e-12));
  EXPECT_TRUE(interpolatePose(from, to, 1.0).isApprox(to, 1e-12));
  const Eigen::Isometry3d half = interpolatePose(from, to, 0.5);
  EXPECT_TRUE(half.translation().isApprox(Eigen::Vector3d(0.5, 1.0, 1.5), 1e-12));
  EXPECT_NEAR(Eigen::AngleAxisd(half.linear()).angle(), M_PI / 4, 1e-12);
}

}  // namespace
}  // namespace deformable_sim::core
