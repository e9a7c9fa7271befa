// How a finite-element body answers contact impulses (core/bodies/implicit_response.h): impulses
// gathered node by node answer as one solve of them all, at the nodes contact looks at and at
// every other; points kept as sums of their nodes' answers answer as their nodes do; the columns
// are kept from step to step while the step's matrix stands, and solved again when its holds
// change or its elements turn.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <memory>

#include "deformable_sim/core/bodies/finite_element_body.h"
#include "deformable_sim/core/bodies/implicit_response.h"
#include "deformable_sim/core/elements/box_mesh.h"

namespace dc = deformable_sim::core;

namespace {

constexpr double kDt = 0.01;

/// A soft, warped 4 x 4 x 4 cm cube of 2 x 2 x 2 cells, stepped once under gravity.
std::unique_ptr<dc::Body> steppedCube() {
  dc::BodySettings settings;
  settings.material = {1.0e5, 0.3, 100.0};
  settings.effects.warping = true;
  settings.effects.gravity = Eigen::Vector3d(0.0, 0.0, -9.81);
  settings.solver.method = dc::SolverSettings::Method::kConjugateGradient;
  std::unique_ptr<dc::Body> body =
      dc::makeBody("cube",
                   dc::makeBoxMesh(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(0.04),
                                   Eigen::Vector3i::Constant(2)),
                   settings);
  body->step(kDt);
  return body;
}

/// The body turning about z through its centre at `rate` rad/s.
void spin(dc::Body& body, double rate) {
  const Eigen::Vector3d centre = Eigen::Vector3d::Constant(0.02);
  Eigen::VectorXd v(body.positions().size());
  for (int i = 0; i < body.numNodes(); ++i) {
    v.segment<3>(3 * i) =
        Eigen::Vector3d(0.0, 0.0, rate).cross(body.positions().segment<3>(3 * i) - centre);
  }
  body.setState(body.positions(), v);
}

}  // namespace

TEST(ImplicitResponse, GatheredImpulsesAnswerAsOneSolveOfThemAll) {
  std::unique_ptr<dc::Body> cube = steppedCube();
  dc::FiniteElementBody& body = *cube->finiteElements();
  dc::ImplicitResponse response(body);
  response.begin(body);
  response.clearImpulses();
  const Eigen::Vector3d first(0.01, -0.02, 0.03), second(-0.005, 0.0, 0.02);
  response.addImpulse(3, first);
  response.addImpulse(20, second);
  response.addImpulse(3, first);  // twice on the same node
  EXPECT_EQ(response.solves(), 6);

  Eigen::VectorXd impulses = Eigen::VectorXd::Zero(3 * body.numNodes());
  Eigen::VectorXd expected(impulses.size());
  impulses.segment<3>(9) = 2.0 * first;
  impulses.segment<3>(60) = second;
  body.solveLastStep(impulses, expected);
  Eigen::VectorXd dv(impulses.size());
  response.velocityChanges(dv);
  const double scale = expected.norm();
  ASSERT_GT(scale, 0.0);
  EXPECT_LT((dv - expected).norm(), 1e-12 * scale);
  for (int j : {3, 20, 0, 26}) {  // two with columns, two without
    EXPECT_LT((response.velocityChange(j) - expected.segment<3>(3 * j)).norm(), 1e-12 * scale)
        << "node " << j;
  }
  // A node that starts touching after the impulses sees them too.
  const Eigen::Matrix3d late = response.block(13, 13);
  EXPECT_GT(late.trace(), 0.0);
  EXPECT_LT((response.velocityChange(13) - expected.segment<3>(39)).norm(), 1e-12 * scale);
  response.clearImpulses();
  EXPECT_EQ(response.velocityChange(3), Eigen::Vector3d::Zero());
}

TEST(ImplicitResponse, KeepsItsColumnsWhileTheMatrixStandsAndSolvesAgainWhenItDoesNot) {
  std::unique_ptr<dc::Body> cube = steppedCube();
  dc::FiniteElementBody& body = *cube->finiteElements();
  dc::ImplicitResponse response(body);
  response.begin(body);
  const Eigen::Matrix3d first = response.block(3, 3);
  EXPECT_EQ(response.solves(), 3);

  // A step of the same body falling: the same matrix but for its rotations, which barely turn.
  body.step(kDt);
  response.begin(body);
  EXPECT_EQ(response.kept(), 1);
  EXPECT_EQ(response.block(3, 3), first);
  EXPECT_EQ(response.solves(), 0);

  // A node held from now on: its row is another, the columns are solved again.
  body.holdNodeAt(0, body.positions().head<3>());
  body.step(kDt);
  response.begin(body);
  EXPECT_EQ(response.kept(), 0);
  response.block(3, 3);
  EXPECT_EQ(response.solves(), 3);
  body.releaseNode(0);

  // Turning slowly (0.5 degrees a step) keeps them; fast (6 degrees a step), not. A state set
  // from outside starts them again either way.
  for (const double rate : {1.0, 10.0}) {
    spin(body, rate);
    body.step(kDt);
    response.begin(body);
    EXPECT_EQ(response.kept(), 0) << "rate " << rate;
    response.block(3, 3);
    body.step(kDt);
    response.begin(body);
    EXPECT_EQ(response.kept(), rate < 5.0 ? 1 : 0) << "rate " << rate;
  }
}

TEST(ImplicitResponse, KeptPointsAnswerAsTheirNodesDo) {
  std::unique_ptr<dc::Body> cube = steppedCube();
  dc::FiniteElementBody& body = *cube->finiteElements();
  dc::ImplicitResponse kept(body), by_node(body);
  for (dc::ImplicitResponse* r : {&kept, &by_node}) {
    r->begin(body);
    r->clearImpulses();
  }
  // Two corners of a surface on grid nodes, and a point between them (their nodes merged).
  const int first_nodes[] = {3, 4, 12, 13}, second_nodes[] = {13, 14, 22, 23};
  const double first_weights[] = {0.1, 0.2, 0.3, 0.4}, second_weights[] = {0.25, 0.25, 0.25, 0.25};
  for (int node : {3, 4, 12, 13, 14, 22, 23}) kept.block(node, node);  // all touching first
  const int first = kept.keepPoint(first_nodes, first_weights, 4);
  const int second = kept.keepPoint(second_nodes, second_weights, 4);
  const int both[] = {first, second};
  const double along[] = {0.6, 0.4};
  const int between = kept.keepSum(both, along, 2);
  ASSERT_GE(between, 0);
  const int merged_nodes[] = {3, 4, 12, 13, 14, 22, 23};
  const double merged_weights[] = {0.06, 0.12, 0.18, 0.24 + 0.1, 0.1, 0.1, 0.1};

  // Its compliance from the kept sum is the double sum over its nodes' blocks.
  Eigen::Matrix3d from_sum, expected = Eigen::Matrix3d::Zero();
  ASSERT_TRUE(kept.keptCompliance(between, merged_nodes, merged_weights, 7, from_sum));
  for (int a = 0; a < 7; ++a) {
    for (int b = 0; b < 7; ++b) {
      expected +=
          merged_weights[a] * merged_weights[b] * by_node.block(merged_nodes[a], merged_nodes[b]);
    }
  }
  EXPECT_LT((from_sum - expected).norm(), 1e-12 * expected.norm());

  // An impulse there answers as the same impulse spread over the nodes one by one.
  const Eigen::Vector3d impulse(0.02, -0.01, 0.03);
  kept.addPointImpulse(between, merged_nodes, merged_weights, 7, impulse);
  for (int k = 0; k < 7; ++k) by_node.addImpulse(merged_nodes[k], merged_weights[k] * impulse);
  Eigen::VectorXd dv(3 * body.numNodes()), expected_dv(3 * body.numNodes());
  kept.velocityChanges(dv);
  by_node.velocityChanges(expected_dv);
  EXPECT_LT((dv - expected_dv).norm(), 1e-12 * expected_dv.norm());
  for (int j : merged_nodes) {
    EXPECT_LT((kept.velocityChange(j) - expected_dv.segment<3>(3 * j)).norm(),
              1e-12 * expected_dv.norm());
  }

  // A node that starts touching after the point was kept leaves its sum stale: the compliance is
  // refused and impulses go node by node, as exactly.
  kept.block(26, 26);
  EXPECT_FALSE(kept.keptCompliance(between, merged_nodes, merged_weights, 7, from_sum));
  kept.addPointImpulse(between, merged_nodes, merged_weights, 7, impulse);
  for (int k = 0; k < 7; ++k) by_node.addImpulse(merged_nodes[k], merged_weights[k] * impulse);
  kept.velocityChanges(dv);
  by_node.velocityChanges(expected_dv);
  EXPECT_LT((dv - expected_dv).norm(), 1e-12 * expected_dv.norm());
  EXPECT_EQ(kept.keepSum(both, along, 2), -1);
}

TEST(ImplicitResponse, ACornersSumIsKeptFromStepToStepWhileItsColumnsAre) {
  std::unique_ptr<dc::Body> cube = steppedCube();
  dc::FiniteElementBody& body = *cube->finiteElements();
  dc::ImplicitResponse response(body);
  const int nodes[] = {3, 4, 12, 13};
  const double weights[] = {0.1, 0.2, 0.3, 0.4};
  const auto expected = [&]() {
    Eigen::Matrix3d w = Eigen::Matrix3d::Zero();
    for (int a = 0; a < 4; ++a) {
      for (int b = 0; b < 4; ++b) w += weights[a] * weights[b] * response.block(nodes[a], nodes[b]);
    }
    return w;
  };
  response.begin(body);
  response.clearImpulses();
  const int corner = response.keepCorner(7, nodes, weights, 4);
  body.step(kDt);  // the columns stand
  response.begin(body);
  response.clearImpulses();
  EXPECT_EQ(response.keepCorner(7, nodes, weights, 4), corner);
  EXPECT_EQ(response.solves(), 0);
  Eigen::Matrix3d w;
  ASSERT_TRUE(response.keptCompliance(corner, nodes, weights, 4, w));
  EXPECT_LT((w - expected()).norm(), 1e-12 * w.norm());
  // A node starts touching: the sum is taken again, over it too.
  response.block(26, 26);
  EXPECT_FALSE(response.keptCompliance(corner, nodes, weights, 4, w));
  const int again = response.keepCorner(7, nodes, weights, 4);
  ASSERT_TRUE(response.keptCompliance(again, nodes, weights, 4, w));
  EXPECT_LT((w - expected()).norm(), 1e-12 * w.norm());
}
