// Contact in contact space (core/contact/contact_problem.h) on point masses, whose Delassus
// operator is known in closed form: a point stopped on a fixed ground by -m v_n, a block on a
// slope that sticks below μ and slides at exactly μ λ_n above it, a two-body stack matching the
// LCP's solution found by trying every active set, contacts that separate taking nothing, a warm
// start that saves sweeps, and random problems whose answers always keep to the cone and, once
// converged, to complementarity. The solve allocates nothing and repeats its bits.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <random>
#include <vector>

#include "deformable_sim/core/contact/contact_problem.h"
#include "malloc_counter.h"

namespace dc = deformable_sim::core;

namespace {

constexpr double kGravity = 9.81;  // m/s²
constexpr double kDt = 0.01;       // s

/// Point masses (body 0 is the fixed ground, infinite mass) and contacts between them: the
/// textbook case whose Delassus operator is W_ij = sum over shared bodies b of ±I / m_b.
struct PointMasses {
  struct Contact {
    int first = 0, second = 0;  ///< the normal points out of `second` into `first`
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
    double friction = 0.0;
    double target = 0.0;  ///< least normal velocity, m/s
  };
  std::vector<double> masses{0.0};                                   ///< kg; 0: fixed
  std::vector<Eigen::Vector3d> velocities{Eigen::Vector3d::Zero()};  ///< free, m/s
  std::vector<Contact> contacts;

  int addBody(double mass, const Eigen::Vector3d& velocity) {
    masses.push_back(mass);
    velocities.push_back(velocity);
    return static_cast<int>(masses.size()) - 1;
  }
  double inverseMass(int b) const { return masses[b] > 0.0 ? 1.0 / masses[b] : 0.0; }
  /// +1 if body b is contact c's first body, -1 if its second, 0 otherwise.
  double sign(const Contact& c, int b) const {
    return c.first == b ? 1.0 : c.second == b ? -1.0 : 0.0;
  }
  /// The world block of W: velocity of contact i per unit impulse at contact j.
  Eigen::Matrix3d worldBlock(int i, int j) const {
    double w = 0.0;
    for (int b = 1; b < static_cast<int>(masses.size()); ++b) {
      w += sign(contacts[i], b) * sign(contacts[j], b) * inverseMass(b);
    }
    return w * Eigen::Matrix3d::Identity();
  }
  /// Fills `problem`, one coupling per pair of contacts that share a moving body.
  void fill(dc::ContactProblem& problem) const {
    const int n = static_cast<int>(contacts.size());
    problem.begin(n);
    for (int i = 0; i < n; ++i) {
      const Contact& c = contacts[i];
      const Eigen::Matrix3d frame = dc::contactFrameFor(c.normal);
      const Eigen::Vector3d relative = velocities[c.first] - velocities[c.second];
      problem.setContact(i, frame, c.friction, frame.transpose() * relative, c.target);
    }
    for (int i = 0; i < n; ++i) {
      problem.addDiagonal(i, problem.inContactFrames(i, i, worldBlock(i, i)));
      for (int j = i + 1; j < n; ++j) {
        const Eigen::Matrix3d w = worldBlock(i, j);
        if (!w.isZero(0.0)) problem.addCoupling(i, j, problem.inContactFrames(i, j, w));
      }
    }
  }
  /// Each body's velocity after the impulses.
  std::vector<Eigen::Vector3d> after(const dc::ContactProblem& problem) const {
    std::vector<Eigen::Vector3d> v = velocities;
    for (int i = 0; i < static_cast<int>(contacts.size()); ++i) {
      const Eigen::Vector3d impulse = problem.worldImpulse(i);
      v[contacts[i].first] += inverseMass(contacts[i].first) * impulse;
      v[contacts[i].second] -= inverseMass(contacts[i].second) * impulse;
    }
    return v;
  }
};

dc::ContactSolveSettings tight(int sweeps = 1000) {
  dc::ContactSolveSettings settings;
  settings.max_sweeps = sweeps;
  settings.tolerance = 1e-10;
  return settings;
}

/// A block of `mass` at rest on a slope of `angle` (rad) under gravity for one step: the slope's
/// normal tilted about x, the block's free velocity the step's gravity.
PointMasses blockOnSlope(double mass, double angle, double friction) {
  PointMasses scene;
  scene.addBody(mass, Eigen::Vector3d(0, 0, -kGravity * kDt));
  scene.contacts.push_back({1, 0, Eigen::Vector3d(0, -std::sin(angle), std::cos(angle)), friction});
  return scene;
}

/// A vertical stack of `count` equal masses on the ground, all falling at the step's gravity.
PointMasses stack(int count, double mass) {
  PointMasses scene;
  for (int k = 0; k < count; ++k) {
    scene.addBody(mass, Eigen::Vector3d(0, 0, -kGravity * kDt));
    scene.contacts.push_back({k + 1, k, Eigen::Vector3d::UnitZ(), 0.5});
  }
  return scene;
}

}  // namespace

TEST(ContactProblem, FramesAreOrthonormalAndRightHanded) {
  const std::vector<Eigen::Vector3d> normals = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ(),
                                                Eigen::Vector3d(1, 2, -3).normalized(),
                                                Eigen::Vector3d(-0.3, 0.1, 0.2).normalized()};
  for (const Eigen::Vector3d& n : normals) {
    const Eigen::Matrix3d frame = dc::contactFrameFor(n);
    EXPECT_TRUE((frame.transpose() * frame).isIdentity(1e-14));
    EXPECT_NEAR(frame.determinant(), 1.0, 1e-14);
    EXPECT_TRUE(frame.col(0).isApprox(n));
  }
}

TEST(ContactProblem, AFallingPointIsStoppedOnFixedGroundByMinusMTimesItsNormalVelocity) {
  const double mass = 2.5, approach = -1.2;  // kg, m/s
  PointMasses scene;
  scene.addBody(mass, Eigen::Vector3d(0, 0, approach));
  scene.contacts.push_back({1, 0, Eigen::Vector3d::UnitZ(), 0.5});
  dc::ContactProblem problem;
  scene.fill(problem);
  const dc::ContactSolveReport report = problem.solve(tight());
  EXPECT_TRUE(report.converged);
  EXPECT_LE(report.sweeps, 2);  // one contact: one exact update, one sweep to see it done
  EXPECT_NEAR(problem.impulse(0)[0], -mass * approach, 1e-12);
  EXPECT_NEAR(problem.impulse(0).tail<2>().norm(), 0.0, 1e-12);
  EXPECT_NEAR(problem.velocity(0).norm(), 0.0, 1e-12);
}

TEST(ContactProblem, ATargetNormalVelocityPushesOutByExactlyThat) {
  const double mass = 1.5, depth_speed = 0.04;  // kg; m/s that corrects a penetration
  PointMasses scene;
  scene.addBody(mass, Eigen::Vector3d(0.0, 0.0, -0.1));
  scene.contacts.push_back({1, 0, Eigen::Vector3d::UnitZ(), 0.0, depth_speed});
  dc::ContactProblem problem;
  scene.fill(problem);
  EXPECT_TRUE(problem.solve(tight()).converged);
  EXPECT_NEAR(problem.velocity(0)[0], depth_speed, 1e-12);
  EXPECT_NEAR(problem.impulse(0)[0], mass * (depth_speed + 0.1), 1e-12);
}

TEST(ContactProblem, ABlockOnASlopeSticksBelowMuAndSlidesAtExactlyMuTimesItsPushAbove) {
  const double mass = 3.0, friction = 0.5;
  const double sticking = std::atan(friction) - 0.1, sliding = std::atan(friction) + 0.1;
  for (double angle : {sticking, sliding}) {
    const PointMasses scene = blockOnSlope(mass, angle, friction);
    dc::ContactProblem problem;
    scene.fill(problem);
    ASSERT_TRUE(problem.solve(tight()).converged);
    // Gravity's impulse over the step, split along the slope's normal and down its slope.
    const double push = mass * kGravity * kDt * std::cos(angle);
    const double down_slope = mass * kGravity * kDt * std::sin(angle);
    const Eigen::Vector3d& impulse = problem.impulse(0);
    const Eigen::Vector3d& v = problem.velocity(0);
    EXPECT_NEAR(impulse[0], push, 1e-12);
    EXPECT_NEAR(v[0], 0.0, 1e-12);
    if (angle == sticking) {
      EXPECT_NEAR(impulse.tail<2>().norm(), down_slope, 1e-12);
      EXPECT_NEAR(v.tail<2>().norm(), 0.0, 1e-12);
    } else {
      EXPECT_NEAR(impulse.tail<2>().norm(), friction * impulse[0], 1e-12);
      // It slides down at what friction leaves, and friction opposes that slip.
      EXPECT_NEAR(v.tail<2>().norm(), (down_slope - friction * push) / mass, 1e-12);
      EXPECT_NEAR(impulse.tail<2>().normalized().dot(v.tail<2>().normalized()), -1.0, 1e-12);
    }
  }
}

TEST(ContactProblem, ATwoBodyStackMatchesTheLcpSolutionOfEveryActiveSet) {
  // Body 2 on body 1 on the ground, frictionless: a 2-contact LCP, solved here by trying its
  // four active sets, for top bodies falling, resting and pulled up.
  const double bottom = 2.0, top = 0.5;  // kg
  for (double top_velocity : {-3.0, -0.0981, 0.0, 0.5, 4.0}) {
    PointMasses scene;
    scene.addBody(bottom, Eigen::Vector3d(0, 0, -0.0981));
    scene.addBody(top, Eigen::Vector3d(0, 0, top_velocity));
    scene.contacts.push_back({1, 0, Eigen::Vector3d::UnitZ(), 0.0});
    scene.contacts.push_back({2, 1, Eigen::Vector3d::UnitZ(), 0.0});
    dc::ContactProblem problem;
    scene.fill(problem);
    ASSERT_TRUE(problem.solve(tight()).converged);
    ASSERT_EQ(problem.couplings(), 1);
    Eigen::Matrix2d w;
    w << scene.worldBlock(0, 0)(0, 0), scene.worldBlock(0, 1)(0, 0), scene.worldBlock(1, 0)(0, 0),
        scene.worldBlock(1, 1)(0, 0);
    EXPECT_LT(w(0, 1), 0.0);  // pressing on the top lifts the bottom's contact off the ground
    const Eigen::Vector2d free(-0.0981, top_velocity + 0.0981);
    int solutions = 0;
    for (int active = 0; active < 4; ++active) {
      Eigen::Vector2d lambda = Eigen::Vector2d::Zero();
      const bool a0 = active & 1, a1 = active & 2;
      if (a0 && a1) lambda = w.ldlt().solve(-free);
      if (a0 && !a1) lambda[0] = -free[0] / w(0, 0);
      if (!a0 && a1) lambda[1] = -free[1] / w(1, 1);
      const Eigen::Vector2d v = w * lambda + free;
      if ((lambda.array() < -1e-12).any() || (v.array() < -1e-12).any()) continue;
      if (std::abs(lambda.dot(v)) > 1e-12) continue;
      ++solutions;
      EXPECT_NEAR(problem.impulse(0)[0], lambda[0], 1e-9) << "top at " << top_velocity;
      EXPECT_NEAR(problem.impulse(1)[0], lambda[1], 1e-9) << "top at " << top_velocity;
    }
    EXPECT_GE(solutions, 1);  // W positive definite: one solution (two sets give it at rest)
  }
}

TEST(ContactProblem, AStackAtRestCarriesTheWeightAboveEachContact) {
  const int count = 6;
  const double mass = 0.7;
  const PointMasses scene = stack(count, mass);
  dc::ContactProblem problem;
  scene.fill(problem);
  ASSERT_TRUE(problem.solve(tight(5000)).converged);
  for (int k = 0; k < count; ++k) {
    EXPECT_NEAR(problem.impulse(k)[0], (count - k) * mass * kGravity * kDt, 1e-8);
  }
  for (const Eigen::Vector3d& v : scene.after(problem)) EXPECT_LT(v.norm(), 1e-8);
}

TEST(ContactProblem, SeparatingContactsTakeNoImpulseAndNoContactEverPulls) {
  // The top body leaves upwards, the bottom one rests: a warm start that guessed the top held
  // down (a pull) is dropped, and only the ground pushes.
  const double bottom = 2.0, top = 0.5;
  PointMasses scene;
  scene.addBody(bottom, Eigen::Vector3d(0.3, 0, -0.1));
  scene.addBody(top, Eigen::Vector3d(0, 0, 2.0));
  scene.contacts.push_back({1, 0, Eigen::Vector3d::UnitZ(), 0.8});
  scene.contacts.push_back({2, 1, Eigen::Vector3d::UnitZ(), 0.8});
  dc::ContactProblem problem;
  scene.fill(problem);
  problem.setImpulse(1, Eigen::Vector3d(-5.0, 1.0, 0.0));  // a pull and friction with it
  ASSERT_TRUE(problem.solve(tight()).converged);
  EXPECT_EQ(problem.impulse(1), Eigen::Vector3d::Zero());
  EXPECT_GT(problem.velocity(1)[0], 0.0);
  EXPECT_NEAR(problem.impulse(0)[0], bottom * 0.1, 1e-12);
  // A contact whose free velocity already parts takes nothing.
  PointMasses apart;
  apart.addBody(1.0, Eigen::Vector3d(0.2, -0.1, 0.05));
  apart.contacts.push_back({1, 0, Eigen::Vector3d::UnitZ(), 1.0});
  apart.fill(problem);
  ASSERT_TRUE(problem.solve(tight()).converged);
  EXPECT_EQ(problem.impulse(0), Eigen::Vector3d::Zero());
}

TEST(ContactProblem, AWarmStartFromTheLastStepTakesFewerSweeps) {
  const PointMasses scene = stack(8, 1.0);
  dc::ContactProblem problem;
  scene.fill(problem);
  dc::ContactSolveSettings settings;
  settings.max_sweeps = 2000;
  settings.sweeps_before_newton = settings.max_sweeps + 1;  // the sweeps' own warm start
  settings.tolerance = 1e-8;
  const dc::ContactSolveReport cold = problem.solve(settings);
  ASSERT_TRUE(cold.converged);
  std::vector<Eigen::Vector3d> last;
  for (int i = 0; i < problem.size(); ++i) last.push_back(problem.impulse(i));
  // The next step of the resting stack: the same gravity, its bodies' free velocities off by
  // 1e-5 of it (what was left of the last step's stop).
  PointMasses next = scene;
  for (size_t b = 1; b < next.velocities.size(); ++b) next.velocities[b] *= 1.0 + 1e-5;
  next.fill(problem);
  for (int i = 0; i < problem.size(); ++i) problem.setImpulse(i, last[i]);
  const dc::ContactSolveReport warm = problem.solve(settings);
  EXPECT_TRUE(warm.converged);
  EXPECT_LT(warm.sweeps, cold.sweeps / 2) << "cold " << cold.sweeps << ", warm " << warm.sweeps;
}

// A tall stack of light and heavy masses in turn: each sweep passes a change one contact along,
// so the sweeps crawl; Newton, from where 20 of them got, finds the same answer in a few steps.
TEST(ContactProblem, WhereTheSweepsCrawlNewtonFinishesInAFewSteps) {
  PointMasses scene = stack(30, 1.0);
  for (size_t b = 1; b < scene.masses.size(); ++b) scene.masses[b] = b % 2 ? 1.0 : 50.0;
  for (auto& c : scene.contacts) c.normal = Eigen::Vector3d(0.1, 0.0, 1.0).normalized();
  dc::ContactProblem problem;
  scene.fill(problem);
  dc::ContactSolveSettings sweeps_only = tight(100000);
  sweeps_only.sweeps_before_newton = sweeps_only.max_sweeps + 1;
  const dc::ContactSolveReport crawl = problem.solve(sweeps_only);
  ASSERT_TRUE(crawl.converged);
  std::vector<Eigen::Vector3d> by_sweeps;
  for (int i = 0; i < problem.size(); ++i) by_sweeps.push_back(problem.impulse(i));
  scene.fill(problem);
  const dc::ContactSolveReport newton = problem.solve(tight(100000));
  ASSERT_TRUE(newton.converged);
  EXPECT_EQ(newton.sweeps, 20);
  EXPECT_GT(crawl.sweeps, 50 * newton.sweeps);
  EXPECT_GE(newton.newton_steps, 1);
  EXPECT_LE(newton.newton_steps, 5);
  EXPECT_LE(newton.residual, 1e-10);
  const double weight = 25 * 51.0 * kGravity * kDt;  // N s, all the masses' step of weight
  for (int i = 0; i < problem.size(); ++i) {
    EXPECT_NEAR((problem.impulse(i) - by_sweeps[i]).norm(), 0.0, 1e-8 * weight) << i;
  }
}

TEST(ContactProblem, RandomProblemsKeepToTheConeAndConvergeToComplementarity) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), positive(0.2, 2.0), mu(0.0, 1.0);
  const Eigen::Matrix3d kSoft = 0.05 * Eigen::Matrix3d::Identity();  // m/s per N s
  int converged = 0;
  const int problems = 200;
  dc::ContactProblem problem;
  problem.reserve(12, 66);
  for (int p = 0; p < problems; ++p) {
    PointMasses scene;
    const int bodies = 3 + p % 6, contacts = 2 + p % 10;
    for (int b = 0; b < bodies; ++b) {
      scene.addBody(positive(random), Eigen::Vector3d(unit(random), unit(random), unit(random)));
    }
    for (int c = 0; c < contacts; ++c) {
      const int first = 1 + static_cast<int>(random() % bodies);
      int second = static_cast<int>(random() % (bodies + 1));
      if (second == first) second = 0;
      const Eigen::Vector3d normal(unit(random), unit(random), unit(random));
      scene.contacts.push_back(
          {first, second, normal.normalized(), mu(random), 0.1 * unit(random)});
    }
    scene.fill(problem);
    // A little compliance at each contact (as a soft contact has) makes W positive definite:
    // random normals between the same two bodies can otherwise ask for the impossible.
    for (int i = 0; i < problem.size(); ++i) problem.addDiagonal(i, kSoft);
    const dc::ContactSolveReport report = problem.solve(tight(3000));
    converged += report.converged;
    for (int i = 0; i < problem.size(); ++i) {
      const Eigen::Vector3d& l = problem.impulse(i);
      const Eigen::Vector3d& v = problem.velocity(i);
      const double mu_i = scene.contacts[i].friction, target = scene.contacts[i].target;
      // Always, converged or not: it pushes, within its cone.
      EXPECT_GE(l[0], 0.0);
      EXPECT_LE(l.tail<2>().norm(), mu_i * l[0] * (1 + 1e-12) + 1e-15);
      if (!report.converged) continue;
      const double w = scene.worldBlock(i, i)(0, 0) + kSoft(0, 0);
      EXPECT_GE(v[0] - target, -1e-8) << "problem " << p << ", contact " << i;
      EXPECT_LE(std::min(w * l[0], v[0] - target), 1e-8) << "problem " << p << ", contact " << i;
      if (v.tail<2>().norm() > 1e-6) {  // it slides: at the cone's rim, against its slip
        EXPECT_NEAR(l.tail<2>().norm(), mu_i * l[0], 1e-8);
        if (l[0] > 1e-6) {
          EXPECT_LT(l.tail<2>().normalized().dot(v.tail<2>().normalized()), -1.0 + 1e-6);
        }
      }
    }
  }
  EXPECT_EQ(converged, problems);
}

TEST(ContactProblem, AnAnisotropicContactSlidesWithFrictionAgainstItsSlip) {
  // One contact whose tangential compliance differs along its two tangents (a point on a
  // slender body): friction must still oppose the slip, not lean toward the stiffer axis.
  dc::ContactProblem problem;
  problem.begin(1);
  problem.setContact(0, Eigen::Matrix3d::Identity(), 0.3, Eigen::Vector3d(-1.0, 2.0, 1.5));
  Eigen::Matrix3d w;
  w << 1.0, 0.1, 0.0, 0.1, 4.0, 0.5, 0.0, 0.5, 0.5;
  problem.addDiagonal(0, w);
  ASSERT_TRUE(problem.solve(tight(5000)).converged);
  const Eigen::Vector3d& l = problem.impulse(0);
  const Eigen::Vector3d& v = problem.velocity(0);
  EXPECT_NEAR(v[0], 0.0, 1e-9);
  EXPECT_NEAR(l.tail<2>().norm(), 0.3 * l[0], 1e-9);
  EXPECT_NEAR(l.tail<2>().normalized().dot(v.tail<2>().normalized()), -1.0, 1e-9);
}

TEST(ContactProblem, ASolveWithinTheReserveAllocatesNothingAndRepeatsItsBits) {
  const PointMasses scene = stack(10, 1.3);
  dc::ContactProblem problem;
  problem.reserve(10, 45);
  scene.fill(problem);  // a first problem of that size, to warm anything lazy
  problem.solve(tight(200));
  const long before = deformable_sim::test::g_allocations.load();
  scene.fill(problem);
  const dc::ContactSolveReport first = problem.solve(tight(200));
  std::vector<Eigen::Vector3d> impulses;
  const long after = deformable_sim::test::g_allocations.load();
  EXPECT_EQ(after, before);
  EXPECT_GT(first.newton_steps, 0);  // the sweeps' part and Newton's
  for (int i = 0; i < problem.size(); ++i) impulses.push_back(problem.impulse(i));
  scene.fill(problem);
  const dc::ContactSolveReport second = problem.solve(tight(200));
  EXPECT_EQ(first.sweeps, second.sweeps);
  EXPECT_EQ(first.residual, second.residual);
  for (int i = 0; i < problem.size(); ++i) EXPECT_EQ(problem.impulse(i), impulses[i]);
}
