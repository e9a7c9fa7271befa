// Rigid and pseudo-rigid bodies: mass properties from the mesh, Newton-Euler motion, the closed
// form of a homogeneous stretch, agreement with the finite-element model of the same block,
// constraints on material points, and a step whose work does not depend on the mesh.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "deformable_sim/core/bodies/mass_properties.h"
#include "deformable_sim/core/bodies/reduced_body.h"
#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/elements/loads.h"
#include "deformable_sim/core/session/commands.h"
#include "deformable_sim/core/session/simulation.h"

namespace dc = deformable_sim::core;

namespace {

const dc::LinearElasticMaterial kSteelish{2.0e8, 0.3, 1000.0};

dc::Mesh box(const Eigen::Vector3d& size, const Eigen::Vector3i& cells,
             dc::BoxElement element = dc::BoxElement::kTetrahedron) {
  return dc::makeBoxMesh(-0.5 * size, 0.5 * size, cells, element);
}

/// A scene of one rigid steel-like body named "block" (its mesh given to the Simulation).
dc::SceneSpec rigidBlockScene() {
  dc::SceneSpec scene;
  dc::BodySpec spec;
  spec.name = "block";
  spec.model = dc::BodyModel::kRigid;
  spec.material = kSteelish;
  scene.bodies.push_back(spec);
  return scene;
}

std::vector<int> nodesWhere(const dc::Body& body, int axis, double value) {
  std::vector<int> nodes;
  for (int i = 0; i < body.numNodes(); ++i) {
    if (std::abs(body.mesh().positions[i][axis] - value) < 1e-9) nodes.push_back(i);
  }
  return nodes;
}

// Equal and opposite tractions (Pa) on the faces x = -L/2 and x = +L/2.
void pullEnds(dc::Body& body, double length, double traction) {
  const std::vector<dc::Face> boundary = dc::extractBoundary(body.mesh());
  dc::addTractionLoad(body.mesh(), boundary, nodesWhere(body, 0, 0.5 * length), {traction, 0, 0},
                      body.externalForces());
  dc::addTractionLoad(body.mesh(), boundary, nodesWhere(body, 0, -0.5 * length), {-traction, 0, 0},
                      body.externalForces());
}

TEST(MassProperties, BoxOfEveryElementMatchesTheClosedForm) {
  const Eigen::Vector3d size(0.3, 0.2, 0.1);
  for (dc::BoxElement element : {dc::BoxElement::kTetrahedron, dc::BoxElement::kHexahedron,
                                 dc::BoxElement::kWedge, dc::BoxElement::kPyramid}) {
    dc::Mesh mesh = dc::makeBoxMesh({1, 2, 3}, Eigen::Vector3d(1, 2, 3) + size, {3, 2, 2}, element);
    const dc::MassProperties p = dc::massProperties(mesh, 500.0);
    const double m = 500.0 * size.prod();
    EXPECT_NEAR(p.mass, m, 1e-12 * m);
    EXPECT_LT((p.centre - (Eigen::Vector3d(1, 2, 3) + 0.5 * size)).norm(), 1e-12);
    const Eigen::Vector3d s2 = size.cwiseProduct(size);
    const Eigen::Matrix3d expected =
        (m / 12.0 * Eigen::Vector3d(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y()))
            .asDiagonal();
    EXPECT_LT((p.inertia() - expected).norm(), 1e-10 * expected.norm())
        << "element " << static_cast<int>(element);
  }
}

TEST(MassProperties, TurnedBoxHasTheTurnedInertia) {
  // The off-diagonal terms: the box turned by R has inertia R I R^T about its centre.
  dc::Mesh mesh = box({0.3, 0.2, 0.1}, {3, 2, 2}, dc::BoxElement::kHexahedron);
  const dc::MassProperties straight = dc::massProperties(mesh, 500.0);
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (Eigen::Vector3d& p : mesh.positions) p = r * p + Eigen::Vector3d(1, -2, 0.5);
  const dc::MassProperties turned = dc::massProperties(mesh, 500.0);
  const Eigen::Matrix3d expected = r * straight.inertia() * r.transpose();
  EXPECT_GT(std::abs(expected(0, 1)), 1e-3 * expected.norm());
  EXPECT_LT((turned.inertia() - expected).norm(), 1e-12 * expected.norm());
  EXPECT_LT((turned.centre - Eigen::Vector3d(1, -2, 0.5)).norm(), 1e-12);
}

TEST(RigidBody, MomentumGrowsByTheImpulseOfTheForce) {
  dc::ReducedBody body("block", box({0.2, 0.1, 0.05}, {4, 2, 1}), kSteelish, dc::BodyEffects{},
                       dc::SolverSettings{}, dc::BodyModel::kRigid);
  // A wrench: a total force along y and a couple about z, applied at the rest configuration.
  const Eigen::Vector3d force(0.0, 2.0, 0.0);
  dc::addTotalForce(nodesWhere(body, 0, 0.1), 0.5 * force, body.externalForces());
  dc::addTotalForce(nodesWhere(body, 0, -0.1), 0.5 * force, body.externalForces());
  dc::addTotalForce(nodesWhere(body, 0, 0.1), {0, 0.5, 0}, body.externalForces());
  dc::addTotalForce(nodesWhere(body, 0, -0.1), {0, -0.5, 0}, body.externalForces());
  const dc::ReducedDynamics& rigid = body.reduced();
  const double m = rigid.massProperties().mass, h = 1e-3;
  body.step(h);
  // From rest, one step adds exactly the impulse: h F to the momentum, h tau to the angular one.
  EXPECT_LT((m * rigid.linearVelocity() - h * force).norm(), 1e-14);
  EXPECT_LT((rigid.angularMomentum() - h * Eigen::Vector3d(0, 0, 0.1)).norm(), 1e-15);
  for (int k = 1; k < 1000; ++k) body.step(h);
  // The force stays along y at the nodes: the momentum is F t exactly, whatever the turning.
  EXPECT_LT((m * rigid.linearVelocity() - 1.0 * force).norm(), 1e-12);
  // The centre follows F t^2 / 2m up to the step's first-order error, h F t / 2m.
  const Eigen::Vector3d centre = rigid.centre() - rigid.massProperties().centre;
  EXPECT_NEAR(centre.y(), force.y() / (2 * m), 1.01 * h * force.y() / (2 * m));
  // The nodes follow the model: each at c + R a.
  const Eigen::VectorXd& x = body.positions();
  for (int i = 0; i < body.numNodes(); ++i) {
    const Eigen::Vector3d arm =
        body.restPositions().segment<3>(3 * i) - rigid.massProperties().centre;
    EXPECT_LT((x.segment<3>(3 * i) - rigid.position(arm)).norm(), 1e-15);
  }
}

TEST(RigidBody, FreeSpinConservesAngularMomentumAndPrecessesAtTheClosedFormRate) {
  // A square rod (I1 = I2 != I3) spun about an axis off its symmetry axis: its symmetry axis
  // precesses about L at the rate |L| / I1 (torque-free Euler equations).
  dc::ReducedBody body("rod", box({0.05, 0.05, 0.2}, {2, 2, 6}), kSteelish, dc::BodyEffects{},
                       dc::SolverSettings{}, dc::BodyModel::kRigid);
  const dc::ReducedDynamics& rigid = body.reduced();
  const Eigen::Matrix3d inertia = rigid.massProperties().inertia();
  const Eigen::Vector3d omega(3.0, 0.0, 10.0);  // rad/s
  const Eigen::Matrix3d spin = (Eigen::Matrix3d() << 0, -omega.z(), omega.y(), omega.z(), 0,
                                -omega.x(), -omega.y(), omega.x(), 0)
                                   .finished();
  Eigen::VectorXd v(3 * body.numNodes());
  for (int i = 0; i < body.numNodes(); ++i) {
    v.segment<3>(3 * i) =
        spin * (body.restPositions().segment<3>(3 * i) - rigid.massProperties().centre);
  }
  body.setState(body.restPositions(), v);
  const Eigen::Vector3d l0 = rigid.angularMomentum();
  EXPECT_LT((l0 - inertia * omega).norm(), 1e-12 * l0.norm());
  const double energy0 = body.kineticEnergy();
  const double rate = l0.norm() / inertia(0, 0);
  const Eigen::Vector3d axis = l0.normalized();
  // The angle the symmetry axis has swept about L, followed step by step.
  const double h = 1e-3;
  double swept = 0.0;
  Eigen::Vector3d previous = (rigid.gradient().col(2) - axis.dot(rigid.gradient().col(2)) * axis);
  const int steps = 2000;
  for (int k = 0; k < steps; ++k) {
    body.step(h);
    const Eigen::Vector3d e3 = rigid.gradient().col(2);
    const Eigen::Vector3d now = e3 - axis.dot(e3) * axis;
    swept += std::atan2(previous.cross(now).dot(axis), previous.dot(now));
    previous = now;
  }
  EXPECT_EQ(rigid.angularMomentum(), l0);  // bit for bit: the state itself
  EXPECT_NEAR(swept, rate * steps * h, 1e-3 * rate * steps * h);
  EXPECT_NEAR(body.kineticEnergy(), energy0, 1e-4 * energy0);
  // A proper rotation after thousands of updates.
  EXPECT_LT((rigid.gradient().transpose() * rigid.gradient() - Eigen::Matrix3d::Identity()).norm(),
            1e-13);
}

TEST(RigidBody, PendulumOnOneNodeSwingsWithThePhysicalPendulumPeriod) {
  // A bar hung from the node at the centre of its top face, started 3 degrees from vertical.
  const double length = 0.3, g = 9.81, h = 1e-3;
  dc::BodyEffects effects;
  effects.gravity = Eigen::Vector3d(0, 0, -g);
  dc::ReducedBody body("pendulum", box({0.02, 0.02, length}, {2, 2, 6}), kSteelish, effects,
                       dc::SolverSettings{}, dc::BodyModel::kRigid);
  const Eigen::Vector3d top(0, 0, 0.5 * length);
  int pivot = -1;
  for (int i = 0; i < body.numNodes(); ++i) {
    if ((body.mesh().positions[i] - top).norm() < 1e-9) pivot = i;
  }
  ASSERT_GE(pivot, 0);
  const Eigen::Matrix3d tilt = Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitX()).toRotationMatrix();
  Eigen::VectorXd x = body.restPositions();
  for (int i = 0; i < body.numNodes(); ++i)
    x.segment<3>(3 * i) = top + tilt * (x.segment<3>(3 * i) - top);
  body.setState(x, Eigen::VectorXd::Zero(x.size()));
  body.fixNodes({pivot});
  const dc::ReducedDynamics& rigid = body.reduced();
  const double m = rigid.massProperties().mass, d = 0.5 * length;
  const double pivot_inertia = rigid.massProperties().inertia()(0, 0) + m * d * d;
  const double period = 2 * M_PI * std::sqrt(pivot_inertia / (m * g * d));
  // Upward zero crossings of the centre's y, interpolated within the step.
  std::vector<double> crossings;
  double previous = rigid.centre().y(), largest_gap = 0.0;
  for (int k = 1; k <= static_cast<int>(3.2 * period / h); ++k) {
    body.step(h);
    const double y = rigid.centre().y();
    if (previous < 0.0 && y >= 0.0) crossings.push_back((k - 1 + previous / (previous - y)) * h);
    previous = y;
    largest_gap = std::max(largest_gap, (body.positions().segment<3>(3 * pivot) - top).norm());
  }
  ASSERT_GE(crossings.size(), 3u);
  const double measured = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  EXPECT_NEAR(measured, period, 5e-3 * period);
  EXPECT_LT(largest_gap, 1e-12) << "the pivot left its place";
  // The pivot carries the weight (and the small centripetal force of a 3 degree swing).
  EXPECT_NEAR(body.reactionForces().segment<3>(3 * pivot).z(), m * g, 0.01 * m * g);
}

TEST(PseudoRigidBody, UniaxialStretchMatchesTheClosedForm) {
  // A free bar pulled by equal and opposite tractions: F = diag(1 + s/E, 1 - nu s/E, 1 - nu s/E).
  const double length = 0.4, traction = 1.0e5;
  dc::BodyEffects effects;
  effects.warping = true;
  dc::ReducedBody body("bar", box({length, 0.1, 0.1}, {4, 2, 2}), kSteelish, effects,
                       dc::SolverSettings{}, dc::BodyModel::kPseudoRigid);
  pullEnds(body, length, traction);
  const dc::StaticReport report = body.solveStatic(dc::StaticSettings{});
  EXPECT_TRUE(report.converged);
  const double strain = traction / kSteelish.youngs_modulus;
  const Eigen::Vector3d stretch(1 + strain, 1 - kSteelish.poisson_ratio * strain,
                                1 - kSteelish.poisson_ratio * strain);
  const dc::ReducedDynamics& pseudo = body.reduced();
  EXPECT_LT((pseudo.gradient() - Eigen::Matrix3d(stretch.asDiagonal())).norm(), 1e-12);
  EXPECT_LT((pseudo.centre() - pseudo.massProperties().centre).norm(), 1e-15);
  EXPECT_NEAR(body.elasticEnergy(), 0.5 * traction * strain * 0.4 * 0.01,
              1e-9 * traction * strain * 0.004);

  // The dynamics settles on the same stretch (damped, from rest), while the momentum stays zero.
  dc::BodyEffects damped = effects;
  damped.damping = dc::RayleighDamping{200.0, 0.0};
  dc::ReducedBody moving("bar", box({length, 0.1, 0.1}, {4, 2, 2}), kSteelish, damped,
                         dc::SolverSettings{}, dc::BodyModel::kPseudoRigid);
  pullEnds(moving, length, traction);
  for (int k = 0; k < 400; ++k) moving.step(1e-3);
  EXPECT_LT((moving.reduced().gradient() - Eigen::Matrix3d(stretch.asDiagonal())).norm(),
            1e-6 * strain);
  EXPECT_LT(moving.reduced().linearVelocity().norm(), 1e-15);
}

TEST(PseudoRigidBody, AgreesWithTheFiniteElementBlockOnTheMeanStretch) {
  // The same stiff block as finite elements and as a pseudo-rigid body, pulled at both ends. Its
  // stress is uniaxial and uniform, which linear elements represent exactly: the mean stretches
  // agree to the solver's tolerance (documented: 1e-4 of the strain).
  const double length = 0.2, traction = 2.0e5;
  dc::BodyEffects effects;
  effects.warping = true;
  effects.damping = dc::RayleighDamping{100.0, 0.0};
  double stretch[2];
  for (dc::BodyModel model : {dc::BodyModel::kFiniteElement, dc::BodyModel::kPseudoRigid}) {
    dc::SolverSettings solver;
    solver.tolerance = 1e-10;
    const std::unique_ptr<dc::Body> made =
        dc::makeBody("block", box({length, 0.1, 0.1}, {4, 2, 2}),
                     dc::BodySettings{model, kSteelish, effects, solver});
    dc::Body& body = *made;
    pullEnds(body, length, traction);
    for (int k = 0; k < 50; ++k) body.step(0.01);  // implicit Euler at h >> 1/omega: quasi-static
    const auto mean_x = [&](double face) {
      double sum = 0.0;
      const std::vector<int> nodes = nodesWhere(body, 0, face);
      for (int i : nodes) sum += body.positions()[3 * i];
      return sum / nodes.size();
    };
    stretch[model == dc::BodyModel::kPseudoRigid] =
        (mean_x(0.5 * length) - mean_x(-0.5 * length)) / length;
  }
  const double strain = traction / kSteelish.youngs_modulus;
  EXPECT_NEAR(stretch[1] - 1.0, strain, 1e-9 * strain);
  EXPECT_NEAR(stretch[0], stretch[1], 1e-4 * strain);
}

TEST(PseudoRigidBody, ClampedFaceHoldsItsNodesAndCarriesTheLoad) {
  // Clamped at x = -L/2 and pulled at x = +L/2: the clamp forbids the lateral contraction, so
  // the stretch is the constrained modulus' (lambda + 2 mu), and the reactions balance the load.
  const double length = 0.2, traction = 1.0e5;
  dc::BodyEffects effects;
  effects.warping = true;
  dc::ReducedBody body("block", box({length, 0.1, 0.1}, {4, 2, 2}), kSteelish, effects,
                       dc::SolverSettings{}, dc::BodyModel::kPseudoRigid);
  const std::vector<int> clamp = nodesWhere(body, 0, -0.5 * length);
  body.fixNodes(clamp);
  dc::addTractionLoad(body.mesh(), dc::extractBoundary(body.mesh()),
                      nodesWhere(body, 0, 0.5 * length), {traction, 0, 0}, body.externalForces());
  ASSERT_TRUE(body.solveStatic(dc::StaticSettings{}).converged);
  const double lambda = dc::lameLambda(kSteelish), mu = dc::lameMu(kSteelish);
  EXPECT_NEAR(body.reduced().gradient()(0, 0) - 1.0, traction / (lambda + 2 * mu),
              1e-9 * traction / (lambda + 2 * mu));
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  for (int i : clamp) {
    EXPECT_LT((body.positions().segment<3>(3 * i) - body.restPositions().segment<3>(3 * i)).norm(),
              1e-15);
    total += body.reactionForces().segment<3>(3 * i);
  }
  EXPECT_LT((total + Eigen::Vector3d(traction * 0.01, 0, 0)).norm(), 1e-9 * traction * 0.01);
}

TEST(RigidBody, StepWorkDoesNotDependOnTheMesh) {
  // A rigid body under gravity and a constant wrench: its steps never compute a node nor sum
  // the nodal forces again; the nodes are computed once, when asked for.
  dc::BodyEffects effects;
  effects.gravity = Eigen::Vector3d(0, 0, -9.81);
  effects.damping = dc::RayleighDamping{0.5, 0.0};
  for (const Eigen::Vector3i& cells : {Eigen::Vector3i(1, 1, 1), Eigen::Vector3i(24, 24, 24)}) {
    dc::ReducedBody body("block", box({0.2, 0.2, 0.2}, cells), kSteelish, effects,
                         dc::SolverSettings{}, dc::BodyModel::kRigid);
    dc::addTotalForce(nodesWhere(body, 0, 0.1), {0, 0, 5}, body.externalForces());
    for (int k = 0; k < 100; ++k) body.step(1e-3);
    EXPECT_EQ(body.nodeUpdates(), 0) << cells.transpose();
    EXPECT_EQ(body.loadSums(), 1) << cells.transpose();
    body.positions();
    body.velocities();
    EXPECT_EQ(body.nodeUpdates(), 1);
  }
}

TEST(RigidBody, HangingFromThreeNodesItsReactionsCarryItsWeight) {
  dc::BodyEffects effects;
  effects.gravity = Eigen::Vector3d(0, 0, -9.81);
  dc::ReducedBody body("plate", box({0.2, 0.2, 0.02}, {2, 2, 1}), kSteelish, effects,
                       dc::SolverSettings{}, dc::BodyModel::kRigid);
  std::vector<int> corners;
  for (int i : nodesWhere(body, 2, 0.01)) {
    const Eigen::Vector3d p = body.mesh().positions[i];
    if (std::abs(p.x()) > 0.09 && std::abs(p.y()) > 0.09 && (p.y() > 0.0 || p.x() > 0.0)) {
      corners.push_back(i);
    }
  }
  ASSERT_EQ(corners.size(), 3u);  // (+,+), (+,-), (-,+): not on a line
  body.fixNodes(corners);
  for (int k = 0; k < 10; ++k) body.step(0.01);
  const double weight = body.reduced().massProperties().mass * 9.81;
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  for (int i : corners) {
    total += body.reactionForces().segment<3>(3 * i);
    EXPECT_LT((body.positions().segment<3>(3 * i) - body.restPositions().segment<3>(3 * i)).norm(),
              1e-15);
  }
  EXPECT_LT((total - Eigen::Vector3d(0, 0, weight)).norm(), 1e-9 * weight);
  EXPECT_LT(body.reduced().linearVelocity().norm(), 1e-15);
  // Statically the same; a free body under gravity has no equilibrium and says so.
  EXPECT_TRUE(body.solveStatic(dc::StaticSettings{}).converged);
  body.releaseNodes(corners);
  EXPECT_FALSE(body.solveStatic(dc::StaticSettings{}).converged);
}

TEST(RigidBody, NewMaterialKeepsTheVelocitiesAndTheNodesFollow) {
  dc::ReducedBody body("block", box({0.2, 0.1, 0.05}, {2, 1, 1}), kSteelish, dc::BodyEffects{},
                       dc::SolverSettings{}, dc::BodyModel::kRigid);
  const Eigen::Matrix3d spin =
      (Eigen::Matrix3d() << 0, -2, 1, 2, 0, -3, -1, 3, 0).finished();  // omega = (3, 1, 2)
  Eigen::VectorXd v(3 * body.numNodes());
  const Eigen::Vector3d centre = body.reduced().massProperties().centre;
  for (int i = 0; i < body.numNodes(); ++i) {
    v.segment<3>(3 * i) =
        Eigen::Vector3d(0.1, 0, 0) + spin * (body.restPositions().segment<3>(3 * i) - centre);
  }
  body.setState(body.restPositions(), v);
  EXPECT_LT((body.reduced().angularVelocity() - Eigen::Vector3d(3, 1, 2)).norm(), 1e-12);
  EXPECT_LT((body.velocities() - v).norm(), 1e-12);
  const double energy = body.kineticEnergy();
  dc::LinearElasticMaterial heavier = kSteelish;
  heavier.density *= 3.0;
  dc::BodyTuning tuning;
  tuning.material = heavier;
  body.tune(tuning);
  EXPECT_LT((body.reduced().angularVelocity() - Eigen::Vector3d(3, 1, 2)).norm(), 1e-12);
  EXPECT_LT((body.velocities() - v).norm(), 1e-12);
  EXPECT_NEAR(body.kineticEnergy(), 3.0 * energy, 1e-12 * energy);
}

TEST(RigidBody, WatchdogUndoesAStepThatOverflows) {
  const dc::SceneSpec scene = rigidBlockScene();
  std::vector<dc::Mesh> meshes{box({0.2, 0.2, 0.2}, {1, 1, 1})};
  dc::Simulation simulation(scene, std::move(meshes));
  dc::Body& body = simulation.bodies()[0];
  std::vector<dc::StepReport> reports;
  body.externalForces()[0] = 1e308;  // the resultant overflows
  body.externalForces()[3] = 1e308;
  simulation.step(reports);
  EXPECT_TRUE(reports[0].recovered);
  EXPECT_EQ(simulation.recoveries(0), 1);
  EXPECT_EQ(body.positions(), body.restPositions());
  EXPECT_EQ(body.velocities().norm(), 0.0);
  body.externalForces().setZero();
  simulation.step(reports);
  EXPECT_FALSE(reports[0].recovered);
}

TEST(RigidBody, WrenchCommandsActFromTheNextStep) {
  // A wrench command rewrites the nodal forces; the next step sums them again, and clearing the
  // wrench stops the push.
  dc::Simulation simulation(rigidBlockScene(), {box({0.2, 0.2, 0.2}, {2, 2, 2})});
  dc::CommandProcessor commands(simulation);
  const auto& body = dynamic_cast<const dc::ReducedBody&>(simulation.bodies()[0]);
  const double m = body.reduced().massProperties().mass, h = simulation.dt();
  std::vector<dc::StepReport> reports;
  simulation.step(reports);
  dc::WrenchCommand push;
  push.source = "hand";
  push.body = "block";
  push.nodes.whole_body = true;
  push.force = Eigen::Vector3d(0, 3, 0);
  push.torque = Eigen::Vector3d(0, 0, 0.2);
  commands.apply(push);
  simulation.step(reports);
  EXPECT_LT((m * body.reduced().linearVelocity() - h * push.force).norm(), 1e-14);
  EXPECT_LT((body.reduced().angularMomentum() - h * push.torque).norm(), 1e-15);
  push.force.setZero();
  push.torque.setZero();
  commands.apply(push);  // a zero wrench clears it
  simulation.step(reports);
  EXPECT_LT((m * body.reduced().linearVelocity() - h * Eigen::Vector3d(0, 3, 0)).norm(), 1e-14);
  EXPECT_EQ(body.loadSums(), 3);
}

TEST(BodyModels, ReducedBodiesHaveNoElements) {
  dc::ReducedBody body("block", box({0.2, 0.2, 0.2}, {2, 2, 2}), kSteelish, dc::BodyEffects{},
                       dc::SolverSettings{}, dc::BodyModel::kPseudoRigid);
  EXPECT_EQ(body.finiteElements(), nullptr);
  dc::BodyEffects plastic;
  plastic.plasticity = dc::PlasticitySettings{};
  try {
    dc::ReducedBody("block", box({0.2, 0.2, 0.2}, {2, 2, 2}), kSteelish, plastic,
                    dc::SolverSettings{}, dc::BodyModel::kRigid);
    FAIL() << "a rigid body took plasticity";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "body 'block': plasticity needs a finite-element body (rigid bodies deform "
                 "homogeneously or not at all)");
  }
}

}  // namespace
