// Dynamics and statics of a whole body: free fall, momentum, constraints, reactions, solvers.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "body_meters.h"
#include "deformable_sim/core/bodies/finite_element_body.h"
#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/elements/selection.h"
#include "deformable_sim/core/outputs/strain.h"
#include "thrown_message.h"

namespace dc = deformable_sim::core;
using deformable_sim::test::momentum;

namespace {

const dc::LinearElasticMaterial kSoft{1.0e5, 0.3, 1000.0};

dc::FiniteElementBody makeBeam(bool warping, std::optional<Eigen::Vector3d> gravity,
                               dc::SolverSettings solver = {}) {
  dc::BodyEffects effects;
  effects.warping = warping;
  effects.gravity = gravity;
  return dc::FiniteElementBody("beam",
                               dc::makeBoxMesh({0, -0.05, -0.05}, {1.0, 0.05, 0.05}, {10, 2, 2}),
                               kSoft, effects, solver);
}

std::vector<int> clampedEnd(const dc::Body& body) {
  dc::NodeSelection end;
  end.kind = dc::NodeSelection::Kind::kBox;
  end.box = {{-1e-9, -1, -1}, {1e-9, 1, 1}};
  return dc::selectNodes(body.mesh(), end);
}

Eigen::Vector3d total(const Eigen::VectorXd& stacked) {
  return stacked.reshaped(3, stacked.size() / 3).rowwise().sum();
}

}  // namespace

TEST(Body, FallsFreelyWithExactlyGravitysAcceleration) {
  const Eigen::Vector3d g(0, 0, -9.81);
  dc::SolverSettings tight;
  tight.tolerance = 1e-13;
  for (bool warping : {false, true}) {
    dc::FiniteElementBody body = makeBeam(warping, g, tight);
    const double dt = 0.01;
    for (int s = 0; s < 50; ++s) body.step(dt);
    // Implicit Euler with a uniform field: v_n = n h g, x_n = x0 + h^2 g n (n + 1) / 2.
    for (int i = 0; i < body.numNodes(); ++i) {
      EXPECT_NEAR((body.velocities().segment<3>(3 * i) - 50 * dt * g).norm(), 0.0, 1e-9);
      const Eigen::Vector3d drop =
          body.positions().segment<3>(3 * i) - body.restPositions().segment<3>(3 * i);
      EXPECT_NEAR((drop - dt * dt * g * 50 * 51 / 2).norm(), 0.0, 1e-9);
    }
  }
}

TEST(Body, ConservesMomentumWithoutExternalForces) {
  dc::FiniteElementBody body = makeBeam(true, std::nullopt);
  // Start from a bent, spinning state.
  Eigen::VectorXd x = body.restPositions(), v = Eigen::VectorXd::Zero(x.size());
  for (int i = 0; i < body.numNodes(); ++i) {
    const Eigen::Vector3d p = x.segment<3>(3 * i);
    x[3 * i + 2] += 0.2 * p.x() * p.x();
    v.segment<3>(3 * i) = Eigen::Vector3d(0.0, 0.0, 3.0).cross(p) + Eigen::Vector3d(0.1, 0.2, -0.3);
  }
  body.setState(x, v);
  const Eigen::Vector3d p0 = momentum(body);
  for (int s = 0; s < 100; ++s) {
    const dc::StepReport report = body.step(0.01);
    ASSERT_TRUE(report.solve.converged);
  }
  // Internal forces sum to zero; CG at 1e-6 leaves a small residual.
  EXPECT_NEAR((momentum(body) - p0).norm(), 0.0, 1e-4 * p0.norm());
  EXPECT_TRUE(body.positions().allFinite());
}

TEST(Body, ClampedBeamSettlesAndItsReactionsCarryItsWeight) {
  const Eigen::Vector3d g(0, 0, -9.81);
  for (bool warping : {false, true}) {
    dc::BodyEffects effects;
    effects.warping = warping;
    effects.gravity = g;
    effects.damping = dc::RayleighDamping{5.0, 0.001};
    // Stiff enough to ring at ~1.6 Hz, damped at 2.5/s: at rest after 10 s.
    dc::FiniteElementBody body("beam",
                               dc::makeBoxMesh({0, -0.05, -0.05}, {1.0, 0.05, 0.05}, {10, 2, 2}),
                               {1.0e7, 0.3, 1000.0}, effects, dc::SolverSettings{});
    const std::vector<int> clamp = clampedEnd(body);
    body.fixNodes(clamp);
    for (int s = 0; s < 500; ++s) body.step(0.02);
    double weight = 0.0;
    for (double m : body.nodalMasses()) weight += m * 9.81;
    EXPECT_LT(body.kineticEnergy(), 1e-8);
    // At rest the clamp carries the whole weight.
    EXPECT_NEAR((total(body.reactionForces()) + weight * g.normalized()).norm(), 0.0,
                1e-3 * weight);
    for (int i : clamp) {
      EXPECT_EQ((body.positions() - body.restPositions()).segment<3>(3 * i).norm(), 0.0);
    }
  }
}

TEST(Body, StaticSolveMatchesTheSettledDynamicStateAndBalancesLoads) {
  dc::SolverSettings direct;
  direct.method = dc::SolverSettings::Method::kDirect;
  dc::FiniteElementBody statics = makeBeam(false, Eigen::Vector3d(0, 0, -9.81), direct);
  statics.fixNodes(clampedEnd(statics));
  const dc::StaticReport report = statics.solveStatic({});
  EXPECT_TRUE(report.converged);
  double weight = 0.0;
  for (double m : statics.nodalMasses()) weight += m * 9.81;
  EXPECT_NEAR(total(statics.reactionForces()).z(), weight, 1e-9 * weight);

  dc::SolverSettings tight;
  tight.tolerance = 1e-10;
  dc::FiniteElementBody dynamics = makeBeam(false, Eigen::Vector3d(0, 0, -9.81), tight);
  dynamics.fixNodes(clampedEnd(dynamics));
  // A huge step of implicit Euler with no inertia left is the static solution.
  for (int s = 0; s < 5; ++s) dynamics.step(1000.0);
  EXPECT_LT((dynamics.positions() - statics.positions()).norm(),
            1e-6 * (statics.positions() - statics.restPositions()).norm());
}

TEST(Body, ConjugateGradientAndDirectSolversAgree) {
  dc::SolverSettings cg;
  cg.tolerance = 1e-12;
  cg.max_iterations = 5000;
  dc::SolverSettings direct;
  direct.method = dc::SolverSettings::Method::kDirect;
  dc::FiniteElementBody a = makeBeam(true, Eigen::Vector3d(0, 0, -9.81), cg);
  dc::FiniteElementBody b = makeBeam(true, Eigen::Vector3d(0, 0, -9.81), direct);
  a.fixNodes(clampedEnd(a));
  b.fixNodes(clampedEnd(b));
  for (int s = 0; s < 30; ++s) {
    const dc::StepReport ra = a.step(0.02);
    const dc::StepReport rb = b.step(0.02);
    ASSERT_TRUE(ra.solve.converged);
    EXPECT_GT(ra.solve.iterations, 0);
    EXPECT_LT(rb.solve.relative_residual, 1e-10);
  }
  EXPECT_LT((a.positions() - b.positions()).norm(),
            1e-8 * (b.positions() - b.restPositions()).norm());
}

TEST(Body, FixingAndReleasingAtRunTimeKeepsThePattern) {
  dc::FiniteElementBody body = makeBeam(true, Eigen::Vector3d(0, 0, -9.81));
  const std::vector<int> clamp = clampedEnd(body);
  const int blocks = body.elasticity().stiffness().numBlocks();
  const Eigen::Matrix3d* storage = body.elasticity().stiffness().blocks().data();
  body.fixNodes(clamp);
  for (int s = 0; s < 20; ++s) body.step(0.01);
  body.releaseNodes(clamp);
  EXPECT_EQ(numConstrained(body), 0);
  body.step(0.01);
  // Released: what the clamp held up (the beam's weight) now pulls its end down.
  double end_velocity_z = 0.0;
  for (int i : clamp) end_velocity_z += body.velocities()[3 * i + 2];
  EXPECT_LT(end_velocity_z, 0.0);
  EXPECT_EQ(body.reactionForces().norm(), 0.0);
  EXPECT_EQ(body.elasticity().stiffness().numBlocks(), blocks);
  EXPECT_EQ(body.elasticity().stiffness().blocks().data(), storage);
}

TEST(Body, AHoldOnANodeOutOfRangeIsRefusedAndChangesNothing) {
  dc::FiniteElementBody body = makeBeam(true, std::nullopt);
  const int n = body.numNodes();
  for (const std::vector<int>& nodes : {std::vector<int>{0, -1}, std::vector<int>{n}}) {
    const std::string refused = deformable_sim::test::thrownMessage<std::invalid_argument>(
        [&] { body.fixNodes(nodes); }, "an index out of range was taken");
    EXPECT_EQ(refused, "body 'beam': node index " + std::to_string(nodes.back()) + " out of range");
    EXPECT_EQ(numConstrained(body), 0);
  }
  body.fixNodes({0, 1});
  EXPECT_THROW(body.releaseNodes({0, n + 7}), std::invalid_argument);
  EXPECT_EQ(numConstrained(body), 2) << "a refused release let a node go";
}

TEST(Body, TargetsDragTheNodesExactlyThere) {
  dc::FiniteElementBody body = makeBeam(true, std::nullopt);
  const std::vector<int> clamp = clampedEnd(body);
  std::vector<Eigen::Vector3d> targets;
  for (int i : clamp)
    targets.push_back(body.positions().segment<3>(3 * i) + Eigen::Vector3d(0, 0, 0.1));
  body.setNodeTargets(clamp, targets);
  body.step(0.01);
  for (size_t k = 0; k < clamp.size(); ++k) {
    EXPECT_NEAR((body.positions().segment<3>(3 * clamp[k]) - targets[k]).norm(), 0.0, 1e-12);
  }
  EXPECT_THROW(body.setNodeTargets({clamp[0]}, {Eigen::Vector3d(NAN, 0, 0)}),
               std::invalid_argument);
  EXPECT_THROW(body.fixNodes({body.numNodes()}), std::invalid_argument);
}

TEST(Body, EnergyDecaysAfterReleaseWithImplicitEuler) {
  dc::FiniteElementBody body = makeBeam(true, std::nullopt);
  body.fixNodes(clampedEnd(body));
  Eigen::VectorXd x = body.restPositions();
  for (int i = 0; i < body.numNodes(); ++i) x[3 * i + 2] += 0.3 * std::pow(x[3 * i], 2);
  body.setState(x, Eigen::VectorXd::Zero(x.size()));
  body.step(0.01);
  double previous = body.kineticEnergy() + body.elasticEnergy();
  for (int s = 0; s < 200; ++s) {
    body.step(0.01);
    const double energy = body.kineticEnergy() + body.elasticEnergy();
    EXPECT_LE(energy, previous * (1.0 + 1e-3)) << "step " << s;
    previous = energy;
  }
}

TEST(Body, RejectsBadMeshesAndSettings) {
  dc::Mesh mesh = dc::makeBoxMesh({0, 0, 0}, {1, 1, 1}, {1, 1, 1});
  std::swap(mesh.tetrahedra[2][0], mesh.tetrahedra[2][1]);
  try {
    dc::FiniteElementBody("cube", mesh, kSoft, {}, {});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "body 'cube': tetrahedron 2 has non-positive volume");
  }
  dc::SolverSettings bad;
  bad.tolerance = 0.0;
  EXPECT_THROW(dc::FiniteElementBody("cube", dc::makeBoxMesh({0, 0, 0}, {1, 1, 1}, {1, 1, 1}),
                                     kSoft, {}, bad),
               std::invalid_argument);
  EXPECT_THROW(dc::FiniteElementBody("cube", dc::makeBoxMesh({0, 0, 0}, {1, 1, 1}, {1, 1, 1}),
                                     dc::LinearElasticMaterial{1e6, 0.5, 1000}, {}, {}),
               std::invalid_argument);
}

TEST(Body, ThreadCountChangesNoBit) {
  // More than one chunk of nodes for the dot products and more rows than threads; each
  // preconditioner, since each has its own part in the threads' shared iterations.
  using Preconditioner = dc::SolverSettings::Preconditioner;
  const auto run = [](int threads, Preconditioner preconditioner) {
    dc::SolverSettings solver;
    solver.threads = threads;
    solver.tolerance = 1e-10;
    solver.preconditioner = preconditioner;
    dc::BodyEffects effects;
    effects.gravity = Eigen::Vector3d(0, 0, -9.81);
    dc::FiniteElementBody body("beam",
                               dc::makeBoxMesh({0, -0.1, -0.1}, {1.0, 0.1, 0.1}, {20, 4, 4}), kSoft,
                               effects, solver);
    body.fixNodes(clampedEnd(body));
    for (int s = 0; s < 15; ++s) EXPECT_TRUE(body.step(0.01).solve.converged);
    return Eigen::VectorXd(body.positions() - body.restPositions());
  };
  for (Preconditioner p :
       {Preconditioner::kTwoLevel, Preconditioner::kBlockJacobi, Preconditioner::kFactorization}) {
    const Eigen::VectorXd one = run(1, p);
    const Eigen::VectorXd two = run(2, p);
    const Eigen::VectorXd three = run(3, p);
    // Every count assembles each row and sums each chunk in the same order: bit-identical.
    EXPECT_EQ((one - two).cwiseAbs().maxCoeff(), 0.0) << static_cast<int>(p);
    EXPECT_EQ((two - three).cwiseAbs().maxCoeff(), 0.0) << static_cast<int>(p);
    EXPECT_GT(two.norm(), 1e-3);  // the beam really sagged
  }
}

TEST(Body, ExtrapolatedWarmStartSavesIterationsNotAccuracy) {
  // A swinging cantilever: the same motion to the solver's tolerance, in far fewer iterations.
  const auto swing = [](dc::SolverSettings::WarmStart warm_start, int& total_iterations) {
    dc::SolverSettings solver;
    solver.warm_start = warm_start;
    dc::FiniteElementBody body = makeBeam(true, Eigen::Vector3d(0, 0, -9.81), solver);
    body.fixNodes(clampedEnd(body));
    total_iterations = 0;
    for (int s = 0; s < 100; ++s) total_iterations += body.step(0.01).solve.iterations;
    return Eigen::VectorXd(body.positions() - body.restPositions());
  };
  int extrapolated_iterations = 0, last_velocity_iterations = 0;
  const Eigen::VectorXd a =
      swing(dc::SolverSettings::WarmStart::kExtrapolated, extrapolated_iterations);
  const Eigen::VectorXd b =
      swing(dc::SolverSettings::WarmStart::kLastVelocity, last_velocity_iterations);
  EXPECT_LT(extrapolated_iterations, 0.7 * last_velocity_iterations);
  EXPECT_LT((a - b).norm(), 1e-4 * b.norm());
}

TEST(Body, ABodyAtRestUnderItsLoadCostsOneIterationAStep) {
  // In equilibrium the step's right-hand side is what rounding leaves of forces that cancel.
  // Measured against that alone, CG chased the rounding (737 iterations in these 50 steps);
  // against the load's impulse, one iteration a step keeps the body where it is.
  dc::FiniteElementBody body = makeBeam(true, Eigen::Vector3d(0, 0, -9.81));
  body.fixNodes(clampedEnd(body));
  ASSERT_TRUE(body.solveStatic({}).converged);
  const Eigen::VectorXd rest = body.positions();
  const double sag = (rest - body.restPositions()).norm();
  int iterations = 0;
  for (int s = 0; s < 50; ++s) {
    const dc::StepReport report = body.step(0.01);
    EXPECT_TRUE(report.solve.converged);
    iterations += report.solve.iterations;
  }
  EXPECT_LE(iterations, 50);
  EXPECT_LT((body.positions() - rest).norm(), 1e-6 * sag);
}

TEST(Body, ANewStateStartsANewVelocityHistory) {
  dc::SolverSettings solver;
  solver.coarse_refresh_interval = 1;  // so that only the velocity history can tell them apart
  dc::FiniteElementBody used = makeBeam(true, Eigen::Vector3d(0, 0, -9.81), solver);
  dc::FiniteElementBody fresh = makeBeam(true, Eigen::Vector3d(0, 0, -9.81), solver);
  used.fixNodes(clampedEnd(used));
  fresh.fixNodes(clampedEnd(fresh));
  for (int s = 0; s < 10; ++s) used.step(0.01);
  const Eigen::VectorXd x = used.positions(), v = used.velocities();
  // Steps after setState must not extrapolate from the velocities before it.
  used.setState(x, v);
  fresh.setState(x, v);
  for (int s = 0; s < 5; ++s) {
    used.step(0.01);
    fresh.step(0.01);
  }
  EXPECT_EQ((used.positions() - fresh.positions()).cwiseAbs().maxCoeff(), 0.0);
}

TEST(Body, NodalStrainIsTheRotationFreeStretch) {
  // Stretched 1 % along x, 0.5 % along z, then turned far: every element, and so every node,
  // has the small strain diag(0.01, 0, 0.005) whatever the rotation.
  dc::FiniteElementBody body("block", dc::makeBoxMesh({0, 0, 0}, {0.3, 0.2, 0.1}, {6, 4, 2}), kSoft,
                             dc::BodyEffects{}, dc::SolverSettings{});
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  const Eigen::Matrix3d f = turn * Eigen::Vector3d(1.01, 1.0, 1.005).asDiagonal();
  Eigen::VectorXd x = body.restPositions();
  for (int i = 0; i < body.numNodes(); ++i) x.segment<3>(3 * i) = f * x.segment<3>(3 * i);
  body.setState(x, Eigen::VectorXd::Zero(x.size()));
  std::vector<double> strain;
  dc::nodalStrain(body, strain);
  ASSERT_EQ(static_cast<int>(strain.size()), body.numNodes());
  for (double s : strain) EXPECT_NEAR(s, std::hypot(0.01, 0.005), 1e-12);
}

// Nodes held on a plane (contact sliding along an obstacle) end each step on it, move freely
// along it, and the plane's springs carry the body's weight: a block on a frictionless floor
// under gravity tilted 2 m/s^2 along x slides with exactly that acceleration.
TEST(Body, NodesHeldOnAPlaneStayOnItAndSlideFreelyAlongIt) {
  dc::BodyEffects effects;
  effects.warping = true;
  effects.gravity = Eigen::Vector3d(2.0, 0.0, -9.81);
  effects.damping = dc::RayleighDamping{0.0, 0.01};
  dc::FiniteElementBody body("block", dc::makeBoxMesh({0, 0, 0}, {0.1, 0.1, 0.1}, {2, 2, 2}), kSoft,
                             effects, dc::SolverSettings{});
  double mass = 0.0;
  for (double m : body.nodalMasses()) mass += m;
  const auto centreVelocity = [&body, mass] {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int i = 0; i < body.numNodes(); ++i)
      sum += body.nodalMasses()[i] * body.velocities().segment<3>(3 * i);
    return Eigen::Vector3d(sum / mass);
  };
  const double dt = 0.01;
  Eigen::Vector3d carried = Eigen::Vector3d::Zero();  // by the springs, over the last 20 steps
  for (int s = 1; s <= 60; ++s) {
    std::vector<int> bottom;
    for (int i = 0; i < body.numNodes(); ++i) {
      if (body.restPositions()[3 * i + 2] > 1e-9) continue;
      const Eigen::Vector3d at = body.positions().segment<3>(3 * i);
      body.holdNodeOnPlane(i, Eigen::Vector3d::UnitZ(), Eigen::Vector3d(at.x(), at.y(), 0.0));
      bottom.push_back(i);
    }
    ASSERT_EQ(bottom.size(), 9u);
    body.step(dt);
    for (int i : bottom) {
      ASSERT_LT(std::abs(body.positions()[3 * i + 2]), 1e-5) << "step " << s;
      if (s > 40) carried += body.reactionForces().segment<3>(3 * i);
    }
    body.releasePlaneHolds();
    EXPECT_NEAR(centreVelocity().x(), 2.0 * dt * s, 1e-9 + 1e-6 * s) << "step " << s;
  }
  EXPECT_NEAR(carried.z() / 20.0, 9.81 * mass, 0.01 * 9.81 * mass);
  EXPECT_NEAR(carried.x() / 20.0, 0.0, 1e-9);  // nothing along the plane
}
