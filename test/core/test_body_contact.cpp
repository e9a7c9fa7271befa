// Contact between bodies and of a body with itself: the broad phase (bounding-volume tree over a
// body's surface triangles), the swept node-triangle test, and scenes through the core.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "contact_test_helpers.h"
#include "deformable_sim/core/bodies/contact_participant.h"
#include "deformable_sim/core/contact/aabb_tree.h"
#include "deformable_sim/core/contact/body_surface.h"
#include "deformable_sim/core/contact/edge_edge.h"
#include "deformable_sim/core/contact/node_triangle.h"
#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/session/simulation.h"
#include "scene_builder.h"
#include "simulation_test_helpers.h"

namespace dc = deformable_sim::core;

namespace {

std::vector<dc::Box3> randomBoxes(std::mt19937& random, int count) {
  std::uniform_real_distribution<double> where(-1.0, 1.0), size(0.0, 0.2);
  std::vector<dc::Box3> boxes;
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector3d min(where(random), where(random), where(random));
    boxes.emplace_back(min, min + Eigen::Vector3d(size(random), size(random), size(random)));
  }
  return boxes;
}

std::vector<int> overlapping(const dc::AabbTree& tree, const dc::Box3& box) {
  std::vector<int> found;
  tree.query(box, [&](int item) { found.push_back(item); });
  std::sort(found.begin(), found.end());
  return found;
}

std::vector<int> overlappingByHand(const std::vector<dc::Box3>& boxes, const dc::Box3& box) {
  std::vector<int> found;
  for (size_t k = 0; k < boxes.size(); ++k) {
    if (boxes[k].intersects(box)) found.push_back(static_cast<int>(k));
  }
  return found;
}

}  // namespace

TEST(AabbTree, FindsExactlyTheOverlappingBoxesBeforeAndAfterARefit) {
  std::mt19937 random(7);
  std::vector<dc::Box3> boxes = randomBoxes(random, 500);
  dc::AabbTree tree;
  tree.build(boxes);
  const std::vector<dc::Box3> queries = randomBoxes(random, 50);
  for (const dc::Box3& q : queries) EXPECT_EQ(overlapping(tree, q), overlappingByHand(boxes, q));
  // Every box moves elsewhere: the same tree, refitted, still answers exactly.
  boxes = randomBoxes(random, 500);
  tree.refit(boxes);
  int hits = 0;
  for (const dc::Box3& q : queries) {
    EXPECT_EQ(overlapping(tree, q), overlappingByHand(boxes, q));
    hits += static_cast<int>(overlapping(tree, q).size());
  }
  EXPECT_GT(hits, 0);
  EXPECT_LT(tree.numNodes(), 2 * 500 / dc::AabbTree::kLeafSize * 2);
}

TEST(BodySurface, AreTheBoundaryTrianglesAndNodesOfAnyMesh) {
  for (dc::BoxElement element : {dc::BoxElement::kTetrahedron, dc::BoxElement::kHexahedron}) {
    const dc::Mesh mesh = dc::makeBoxMesh({0, 0, 0}, {0.2, 0.2, 0.1}, {2, 2, 1}, element);
    Eigen::VectorXd x(3 * mesh.numNodes());
    for (int i = 0; i < mesh.numNodes(); ++i) x.segment<3>(3 * i) = mesh.positions[i];
    const dc::BodySurface surface(mesh, x, true);
    EXPECT_EQ(surface.triangles().size(), 2u * (2 * 4 + 4 * 2));  // 8 quads top/bottom, 8 sides
    EXPECT_EQ(surface.nodes().size(), 18u);                       // all nodes are on it
    EXPECT_NEAR(surface.size(), std::sqrt(0.09), 1e-12);
    EXPECT_NEAR(surface.shortestEdge(), 0.1, 1e-12);
    EXPECT_TRUE(surface.adjacent(0, 1));
    EXPECT_FALSE(surface.adjacent(0, 2));  // two cells apart along x
    // Swept upwards by 1 m: the tree's root covers start and end.
    Eigen::VectorXd up = x;
    for (int i = 0; i < mesh.numNodes(); ++i) up[3 * i + 2] += 1.0;
    dc::BodySurface moving(mesh, x, false);
    moving.sweep(up, 0.01);
    EXPECT_NEAR(moving.tree().rootBox().min().z(), -0.01, 1e-12);
    EXPECT_NEAR(moving.tree().rootBox().max().z(), 1.11, 1e-12);
  }
}

TEST(NodeTriangle, ANodeThatCameThroughIsFoundDeepANodeInsideFromTheStartOnlyWhenShallow) {
  dc::SweptTriangle floor;  // z = 0, outward normal +z, still
  floor.start[0] = floor.end[0] = {0, 0, 0};
  floor.start[1] = floor.end[1] = {1, 0, 0};
  floor.start[2] = floor.end[2] = {0, 1, 0};
  dc::NodeTriangleHit hit;
  // Through the triangle within the step, ending 0.5 m below it: found, by the side it came from.
  EXPECT_TRUE(dc::nodeHitsTriangle({{0.2, 0.2, 0.3}, {0.2, 0.2, -0.5}}, floor, 1e-3, 0.01, &hit));
  EXPECT_DOUBLE_EQ(hit.depth, 0.5);
  EXPECT_EQ(hit.normal, Eigen::Vector3d::UnitZ());
  EXPECT_NEAR(hit.weights.sum(), 1.0, 1e-15);
  EXPECT_TRUE(hit.weights.isApprox(Eigen::Vector3d(0.6, 0.2, 0.2)));
  // Deep below from the start (the far side of a body): not this triangle's business.
  EXPECT_FALSE(dc::nodeHitsTriangle({{0.2, 0.2, -0.4}, {0.2, 0.2, -0.5}}, floor, 1e-3, 0.01, &hit));
  // Shallow below from the start (resting on it): found.
  EXPECT_TRUE(
      dc::nodeHitsTriangle({{0.2, 0.2, -0.004}, {0.2, 0.2, -0.005}}, floor, 1e-3, 0.01, &hit));
  // In front, or beside the triangle: not.
  EXPECT_FALSE(dc::nodeHitsTriangle({{0.2, 0.2, 0.3}, {0.2, 0.2, 0.1}}, floor, 1e-3, 0.01, &hit));
  EXPECT_FALSE(dc::nodeHitsTriangle({{0.8, 0.8, 0.3}, {0.8, 0.8, -0.1}}, floor, 1e-3, 0.01, &hit));
  // A triangle that rises through a still node catches it too.
  dc::SweptTriangle rising = floor;
  for (Eigen::Vector3d& corner : rising.end) corner.z() = 0.5;
  EXPECT_TRUE(dc::nodeHitsTriangle({{0.2, 0.2, 0.1}, {0.2, 0.2, 0.1}}, rising, 1e-3, 0.01, &hit));
  EXPECT_NEAR(hit.depth, 0.4, 1e-15);
}

namespace {

/// An edge that moves straight from `from` to `to` (both ends alike).
dc::SweptEdge edgeMoving(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                         const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  return {{p + from, q + from}, {p + to, q + to}};
}

}  // namespace

TEST(EdgeEdge, CrossedEdgesMeetAlongTheirCommonNormalOutOfTheLowerBody) {
  // b: the top edge of a bar along y (its top face and its +x side meet there), still.
  const dc::SweptEdge b = edgeMoving({0, -1, 0}, {0, 1, 0}, {0, 0, 0}, {0, 0, 0});
  const Eigen::Vector3d out_b(1, 0, 1), out_a(0, -1, -1);  // a: a bottom edge along x
  dc::EdgeEdgeHit hit;
  // a comes down through b within the step, ending 1 cm below it.
  const auto a = [](double z0, double z1, double x0 = -1, double x1 = 1) {
    return edgeMoving({x0, 0.2, 0}, {x1, 0.2, 0}, {0, 0, z0}, {0, 0, z1});
  };
  ASSERT_TRUE(dc::edgesMeet(a(0.01, -0.01), b, out_a, out_b, 0.005, 0.002, &hit));
  EXPECT_NEAR(hit.depth, 0.01, 1e-15);
  EXPECT_TRUE(hit.normal.isApprox(Eigen::Vector3d::UnitZ()));
  EXPECT_NEAR(hit.s, 0.5, 1e-15);  // where they cross: x = 0 on a, y = 0.2 on b
  EXPECT_NEAR(hit.t, 0.6, 1e-15);
  // Within the skin above it: touching; beyond the skin: not.
  ASSERT_TRUE(dc::edgesMeet(a(0.01, 0.002), b, out_a, out_b, 0.005, 0.002, &hit));
  EXPECT_NEAR(hit.depth, -0.002, 1e-15);
  EXPECT_FALSE(dc::edgesMeet(a(0.01, 0.006), b, out_a, out_b, 0.005, 0.002, &hit));
  // Deep below from the start (the far sides of two bodies): not.
  EXPECT_FALSE(dc::edgesMeet(a(-0.05, -0.05), b, out_a, out_b, 0.005, 0.002, &hit));
  // Only a little below from the start (resting, sunk in a little): found.
  EXPECT_TRUE(dc::edgesMeet(a(-0.001, -0.001), b, out_a, out_b, 0.005, 0.002, &hit));
  // Nearest points beyond an end of a (an end is a node: nodes and triangles take it): not.
  EXPECT_FALSE(dc::edgesMeet(a(0.01, -0.01, 0.1, 1), b, out_a, out_b, 0.005, 0.002, &hit));
  // Parallel: not.
  const dc::SweptEdge along_b = edgeMoving({0.001, -1, 0}, {0.001, 1, 0}, {0, 0, 0.01}, {0, 0, 0});
  EXPECT_FALSE(dc::edgesMeet(along_b, b, out_a, out_b, 0.005, 0.002, &hit));
  // Side by side in one plane (two rims of a folded strip): their common normal points out of
  // neither body.
  const dc::SweptEdge rim = edgeMoving({-1, 0, -0.1}, {1, 0, 0.1}, {0, 0, 0}, {0, 0, 0});
  const dc::SweptEdge other_rim = edgeMoving({-1, 0, 0}, {1, 0, 0}, {0, 0, 0}, {0, 0, 0});
  EXPECT_FALSE(dc::edgesMeet(rim, other_rim, Eigen::Vector3d(0, -1, -1), Eigen::Vector3d(0, -1, 1),
                             0.005, 0.002, &hit));
}

TEST(BodySurface, FeatureEdgesAreTheConvexRidgesOnly) {
  // A box of 3 x 3 x 1 cells: its 12 edges, in 3 + 3 + 1 pieces each four times; the lines of
  // its faces' grid and the diagonals of their quadrilaterals are flat.
  const dc::Mesh box = dc::makeBoxMesh({0, 0, 0}, {0.3, 0.3, 0.1}, {3, 3, 1});
  Eigen::VectorXd x(3 * box.numNodes());
  for (int i = 0; i < box.numNodes(); ++i) x.segment<3>(3 * i) = box.positions[i];
  const dc::BodySurface surface(box, x, false);
  EXPECT_EQ(surface.edges().size(), 4u * (3 + 3 + 1));
  for (const dc::SurfaceEdge& edge : surface.edges()) {
    const Eigen::Vector3d d = box.positions[edge.nodes[1]] - box.positions[edge.nodes[0]];
    EXPECT_EQ((d.array() != 0.0).count(), 1);  // along an axis
  }
}

// Out of the body at a corner: along its face's normal inside a face, between its faces' normals
// on an edge or a corner (the faces' triangles, weighted by area, summed).
TEST(BodySurface, OutwardAtACornerIsTheNormalOfTheFacesAroundIt) {
  const dc::Mesh box = dc::makeBoxMesh({0, 0, 0}, {0.2, 0.2, 0.1}, {2, 2, 1});
  Eigen::VectorXd x(3 * box.numNodes());
  for (int i = 0; i < box.numNodes(); ++i) x.segment<3>(3 * i) = box.positions[i];
  dc::BodySurface surface(box, x, false);
  surface.sweep(x, 0.0);
  const Eigen::Vector3d centre(0.1, 0.1, 0.05);
  for (int i : surface.nodes()) {
    const Eigen::Vector3d p = box.positions[i], out = surface.outwardAt(i).normalized();
    // Each axis it points along is one whose faces the corner lies on.
    for (int axis = 0; axis < 3; ++axis) {
      const double offset = p[axis] - centre[axis];
      const bool on_face = std::abs(std::abs(offset) - (axis == 2 ? 0.05 : 0.1)) < 1e-12;
      if (on_face) {
        EXPECT_GT(offset > 0.0 ? out[axis] : -out[axis], 0.25) << i;
      } else {
        EXPECT_NEAR(out[axis], 0.0, 1e-12) << i;
      }
    }
  }
  // The middle of the top: straight up, the sum of its triangles' twice-areas (two to six of the
  // top's eight, each 0.005 m^2).
  for (int i = 0; i < box.numNodes(); ++i) {
    if (!box.positions[i].isApprox(Eigen::Vector3d(0.1, 0.1, 0.1))) continue;
    const Eigen::Vector3d up = surface.outwardAt(i);
    EXPECT_NEAR(up.head<2>().norm(), 0.0, 1e-15);
    const double triangles = up.z() / 0.01;
    EXPECT_NEAR(triangles, std::round(triangles), 1e-12);
    EXPECT_GE(triangles, 2.0);
  }
}

namespace {

using deformable_sim::test::centreOfNodes;
using deformable_sim::test::deepestInside;
using deformable_sim::test::totalMomentum;

const dc::LinearElasticMaterial kSoft{1.0e5, 0.3, 100.0};

dc::BodySpec cube(const std::string& name, const Eigen::Vector3d& min, double side,
                  dc::BodyModel model = dc::BodyModel::kFiniteElement, int cells = 2) {
  return deformable_sim::test::boxBody(name, min, min + Eigen::Vector3d::Constant(side),
                                       Eigen::Vector3i::Constant(cells), kSoft, model);
}

/// A scene with contact between bodies on, exact solves (momentum to round-off), no gravity.
dc::SceneSpec bodyContactScene() {
  return deformable_sim::test::SceneBuilder().dt(0.01).warped().contact(0.5, true).solver(
      dc::SolverSettings::Method::kDirect);
}

void setVelocity(dc::Body& body, const Eigen::Vector3d& velocity) {
  Eigen::VectorXd v = body.velocities();
  for (int i = 0; i < body.numNodes(); ++i) v.segment<3>(3 * i) = velocity;
  body.setState(body.positions(), v);
}

}  // namespace

/// Soft, yet stiff enough for a body to answer a blow as a whole within a step (a wave crosses it
/// in less than one): contact acts on nodes, so a mesh this coarse needs it at 5 m/s.
constexpr double kThrownStiffness = 1.0e6;
constexpr int kThrownCells = 2;

TEST(BodyContact, BodiesThrownAtEachOtherStopEachOtherWithMomentumKeptForEveryModelPair) {
  const dc::BodyModel models[] = {dc::BodyModel::kFiniteElement, dc::BodyModel::kPseudoRigid,
                                  dc::BodyModel::kRigid};
  for (dc::BodyModel left : models) {
    for (dc::BodyModel right : models) {
      const std::string pair = std::string(dc::modelName(left)) + "-" + dc::modelName(right);
      dc::SceneSpec spec = bodyContactScene();
      spec.bodies.push_back(cube("left", {-0.35, -0.1, -0.1}, 0.2, left, kThrownCells));
      spec.bodies.push_back(cube("right", {0.15, -0.07, -0.13}, 0.2, right, kThrownCells));
      for (dc::BodySpec& body : spec.bodies) body.material.youngs_modulus = kThrownStiffness;
      dc::Simulation sim = deformable_sim::test::boxMeshSimulation(spec);
      setVelocity(sim.bodies()[0], {5.0, 0.0, 0.0});
      setVelocity(sim.bodies()[1], {-5.0, 0.0, 0.0});
      const double scale = 5.0 * 0.8;  // either body's momentum: 5 m/s, 0.2^3 m^3 of 100 kg/m^3
      const double tolerance = sim.bodyContact()->tolerance(0, 1);
      std::vector<dc::StepReport> reports;
      int touching = 0;
      for (int s = 0; s < 30; ++s) {
        sim.step(reports);
        touching += reports[0].body_contacts;
        // Every pair the contact found is put back to within the tolerance (a node that slips
        // past a triangle's edge within a step is not found: doc/physics.md).
        ASSERT_LE(reports[0].body_penetration, tolerance) << pair << " step " << s;
        ASSERT_LE(totalMomentum(sim.bodies()).norm(), 1e-6 * scale) << pair << " step " << s;
      }
      EXPECT_GT(touching, 0) << pair;
      // They met and stopped each other, each on its own side: no pass-through. (They do not
      // bounce back: backward Euler at 0.01 s damps a blow these stiff cubes would ring with.)
      EXPECT_LT(centreOfNodes(sim.bodies()[0]).x(), centreOfNodes(sim.bodies()[1]).x()) << pair;
      EXPECT_LT(deformable_sim::test::momentum(sim.bodies()[0]).x(), 0.1 * scale) << pair;
    }
  }
}

// Cubes meeting at 10 m/s go 5 cm into each other within a step; the pair's `penetration` says
// so, its `depth` says what the step left: within the tolerance, the same for either side.
TEST(BodyContact, APairsDepthIsWhatTheStepLeftItsPenetrationWhatItCorrected) {
  dc::SceneSpec spec = bodyContactScene();
  spec.bodies.push_back(
      cube("left", {-0.35, -0.1, -0.1}, 0.2, dc::BodyModel::kFiniteElement, kThrownCells));
  spec.bodies.push_back(
      cube("right", {0.15, -0.07, -0.13}, 0.2, dc::BodyModel::kFiniteElement, kThrownCells));
  for (dc::BodySpec& body : spec.bodies) body.material.youngs_modulus = kThrownStiffness;
  dc::Simulation sim = deformable_sim::test::boxMeshSimulation(spec);
  setVelocity(sim.bodies()[0], {5.0, 0.0, 0.0});
  setVelocity(sim.bodies()[1], {-5.0, 0.0, 0.0});
  const double tolerance = sim.bodyContact()->tolerance(0, 1);
  std::vector<dc::StepReport> reports;
  double deepest_found = 0.0;
  for (int s = 0; s < 30; ++s) {
    sim.step(reports);
    const dc::ContactLoad& left = sim.bodyContact()->load(0, 1);
    const dc::ContactLoad& right = sim.bodyContact()->load(1, 0);
    if (left.points == 0) continue;
    deepest_found = std::max(deepest_found, left.penetration);
    EXPECT_LE(left.depth, tolerance) << "step " << s;
    EXPECT_EQ(left.depth, right.depth) << "step " << s;
    EXPECT_LE(left.depth, reports[0].body_penetration) << "step " << s;
  }
  EXPECT_GT(deepest_found, 5.0 * tolerance);
}

TEST(BodyContact, ASoftCubeSquashedToAFifthOfItsHeightBetweenTwoPlatesComesBack) {
  dc::SceneSpec spec = bodyContactScene();
  spec.solver.method = dc::SolverSettings::Method::kConjugateGradient;
  spec.effects.damping = dc::RayleighDamping{2.0, 0.005};
  for (double z : {-0.02, 0.101}) {  // plates just below and just above the cube
    dc::BodySpec plate;
    plate.name = z < 0 ? "bottom" : "top";
    plate.box_mesh = dc::BoxMeshSpec{{-0.15, -0.15, z}, {0.15, 0.15, z + 0.02}, {3, 3, 1}};
    plate.material = kSoft;
    spec.bodies.push_back(plate);
  }
  spec.bodies.push_back(cube("cube", {-0.05, -0.05, 0.0}, 0.1));
  dc::Simulation sim = deformable_sim::test::boxMeshSimulation(spec);
  dc::Body& top = sim.bodies()[1];
  std::vector<int> all(top.numNodes());
  for (int i = 0; i < top.numNodes(); ++i) all[i] = i;
  sim.bodies()[0].fixNodes(all);
  const Eigen::VectorXd rest_top = top.positions();
  const auto moveTopTo = [&](double lowest) {  // the top plate's underside at z = lowest
    std::vector<Eigen::Vector3d> targets(all.size());
    for (int i : all)
      targets[i] = rest_top.segment<3>(3 * i) + Eigen::Vector3d(0, 0, lowest - 0.101);
    top.setNodeTargets(all, targets);
  };
  const double tolerance = sim.bodyContact()->tolerance(1, 2);
  const dc::Body& cube_body = sim.bodies()[2];
  const auto height = [&] {
    const auto z = cube_body.positions().reshaped(3, cube_body.numNodes()).row(2);
    return z.maxCoeff() - z.minCoeff();
  };
  std::vector<dc::StepReport> reports;
  for (int s = 1; s <= 250; ++s) {  // down to 20 % of the height in 2 s, held for half a second
    moveTopTo(std::max(0.02, 0.101 - 0.0005 * s));
    sim.step(reports);
    ASSERT_LE(deepestInside(cube_body, top), tolerance) << s;
    ASSERT_LE(deepestInside(cube_body, sim.bodies()[0]), tolerance) << s;
  }
  EXPECT_LE(height(), 0.02 + 2 * tolerance);
  EXPECT_GT(reports[2].body_contacts, 0);
  moveTopTo(0.3);  // released: the plate leaves in one step
  for (int s = 0; s < 300; ++s) {
    sim.step(reports);
    ASSERT_EQ(reports[2].inverted_elements, 0) << s;
  }
  EXPECT_NEAR(height(), 0.1, 0.005);
  EXPECT_TRUE(cube_body.stateIsFinite());
}

TEST(BodyContact, RunsOnlyWhenTheSceneAndAtLeastTwoBodiesOrOneSelfAskForIt) {
  dc::SceneSpec spec = bodyContactScene();
  spec.bodies.push_back(cube("a", {0, 0, 0}, 0.1));
  spec.bodies.push_back(cube("b", {0.2, 0, 0}, 0.1, dc::BodyModel::kRigid));
  const auto steppedSteps = [](const dc::SceneSpec& scene) {
    dc::Simulation sim = deformable_sim::test::boxMeshSimulation(scene);
    std::vector<dc::StepReport> reports;
    for (int s = 0; s < 3; ++s) sim.step(reports);
    return std::make_pair(sim.bodyContact() != nullptr, sim.bodyContactSteps());
  };
  EXPECT_EQ(steppedSteps(spec), std::make_pair(true, 3L));
  dc::SceneSpec off = spec;
  off.contact->bodies = false;  // obstacles only: nothing of contact between bodies is made
  EXPECT_EQ(steppedSteps(off), std::make_pair(false, 0L));
  dc::SceneSpec alone = spec;  // the other body opts out: nobody left to touch
  alone.bodies[1].effects = spec.effects;
  alone.bodies[1].effects->contact_bodies = false;
  EXPECT_EQ(steppedSteps(alone), std::make_pair(false, 0L));
  dc::SceneSpec self = off;
  self.contact->self = true;  // the finite-element body touches itself; the rigid one cannot
  EXPECT_EQ(steppedSteps(self), std::make_pair(true, 3L));
  self.bodies[0].effects = spec.effects;
  self.bodies[0].effects->contact_self = false;
  EXPECT_EQ(steppedSteps(self), std::make_pair(false, 0L));
}

TEST(ContactParticipant, ComplianceIsOneSymmetricPositiveMatrixForEveryModel) {
  // Pushing a point along n moves it along n by n^T W n per unit impulse, for every direction:
  // W must be the matrix of that quadratic form, and positive (off the axes as well as on them).
  std::mt19937 random(3);
  std::normal_distribution<double> normal;
  for (dc::BodyModel model :
       {dc::BodyModel::kFiniteElement, dc::BodyModel::kPseudoRigid, dc::BodyModel::kRigid}) {
    dc::SceneSpec spec = bodyContactScene();
    spec.bodies.push_back(cube("cube", {0, 0, 0}, 0.1, model));
    dc::Simulation sim = deformable_sim::test::boxMeshSimulation(spec);
    std::vector<dc::StepReport> reports;
    sim.step(reports);  // a finite-element body answers through its last step's matrix
    dc::Body& body = sim.bodies()[0];
    const std::unique_ptr<dc::ContactParticipant> made = body.contactParticipant();
    dc::ContactParticipant& participant = *made;
    participant.begin(spec.dt);
    dc::SurfacePoint point;  // on a vertical edge at a corner, off its nodes
    point.nodes = {17, 26, 26};
    point.weights = {0.3, 0.7, 0.0};
    point.count = 2;
    const Eigen::Matrix3d w = participant.compliance(point);
    EXPECT_TRUE(w.isApprox(w.transpose(), 1e-12)) << dc::modelName(model);
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(w).eigenvalues().minCoeff(), 0.0)
        << dc::modelName(model);
    for (int k = 0; k < 10; ++k) {
      const Eigen::Vector3d n =
          Eigen::Vector3d(normal(random), normal(random), normal(random)).normalized();
      EXPECT_NEAR(n.dot(w * n), participant.inverseMass(point, n), 1e-9 * w.norm())
          << dc::modelName(model);
    }
  }
}

TEST(BodyContact, ABarDroppedAcrossAnotherRestsOnItWhereOnlyTheirEdgesMeet) {
  // Two bars of one cell across, laid crosswise: no node of either lies over the other's face
  // (3 cells along each, nodes at +-1/6 and +-1/2 of the length), so only their edges can meet.
  dc::SceneSpec spec = bodyContactScene();
  spec.effects.gravity = Eigen::Vector3d(0, 0, -9.81);
  spec.effects.damping = dc::RayleighDamping{2.0, 0.005};
  dc::BodySpec lower, upper;
  lower.name = "lower";
  lower.box_mesh = dc::BoxMeshSpec{{-0.3, -0.025, -0.05}, {0.3, 0.025, 0.0}, {3, 1, 1}};
  lower.material = {1.0e6, 0.3, 100.0};
  lower.fixed.push_back(deformable_sim::test::boxSelection({-1, -1, -1}, {-0.3 + 1e-9, 1, 1}));
  lower.fixed.push_back(deformable_sim::test::boxSelection({0.3 - 1e-9, -1, -1}, {1, 1, 1}));
  upper = lower;
  upper.name = "upper";
  upper.fixed.clear();
  upper.box_mesh = dc::BoxMeshSpec{{-0.025, -0.3, 0.005}, {0.025, 0.3, 0.055}, {1, 3, 1}};
  spec.bodies = {lower, upper};
  dc::Simulation sim = deformable_sim::test::boxMeshSimulation(spec);
  const dc::Body& bar = sim.bodies()[1];
  for (const dc::Body& body : sim.bodies()) {
    for (int i = 0; i < body.numNodes(); ++i) {  // no node over the crossing
      const Eigen::Vector3d p = body.restPositions().segment<3>(3 * i);
      ASSERT_GT(std::max(std::abs(p.x()), std::abs(p.y())), 0.05) << body.name() << " " << i;
    }
  }
  const double tolerance = sim.bodyContact()->tolerance(0, 1);
  std::vector<dc::StepReport> reports;
  int edge_steps = 0;
  for (int s = 0; s < 150; ++s) {
    sim.step(reports);
    edge_steps += reports[1].body_contacts > 0;
  }
  const auto z = bar.positions().reshaped(3, bar.numNodes()).row(2);
  EXPECT_GT(edge_steps, 100);
  EXPECT_GT(z.minCoeff(), -tolerance);  // lying on the lower bar's top, not through it
  EXPECT_LT(z.minCoeff(), 0.005);       // it did come down onto it
  EXPECT_LT(bar.kineticEnergy(), 1e-6);
}

// Bodies that touch each other may start inside each other no deeper than their contact
// tolerance (1 % of the smaller one's size, 0.69 mm for these 4 cm cubes); deeper, the scene is
// refused with both names and the depth. Without contact between them, they may overlap.
TEST(BodyContact, BodiesStartedDeeperInsideEachOtherThanTheToleranceAreRefused) {
  const auto overlapping = [](double depth, bool bodies) {
    dc::SceneSpec spec = bodyContactScene();
    spec.contact->bodies = bodies;
    spec.bodies.push_back(cube("lower", {0, 0, 0}, 0.04));
    spec.bodies.push_back(cube("upper", {0, 0, 0.04 - depth}, 0.04));
    return deformable_sim::test::boxMeshSimulation(spec);
  };
  EXPECT_NO_THROW(overlapping(0.0005, true).refuseBodiesInsideEachOther());
  EXPECT_NO_THROW(overlapping(0.009, false).refuseBodiesInsideEachOther());
  try {
    overlapping(0.009, true).refuseBodiesInsideEachOther();
    FAIL() << "two cubes 9 mm into each other were not refused";
  } catch (const dc::SpecError& e) {
    EXPECT_EQ(e.key(), "bodies[1]");
    EXPECT_STREQ(e.what(),
                 "bodies[1]: body 'upper' starts 9.0 mm inside body 'lower'; bodies may start at "
                 "most 0.7 mm into each other (1 % of the smaller one's size): place them apart");
  }
}
