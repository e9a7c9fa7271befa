// What the node's ~mesh, ~markers and a replay's bag draw and how mesh obstacles are recorded
// once: the drawn corners follow the body, coloured by its strain; held and fixed nodes, groups
// and wrench arrows are drawn where they are; triangle meshes survive flat arrays; the catalogue
// lists a mesh's triangles until they are recorded, then names it by id.
#include <gtest/gtest.h>

#include "deformable_sim/core/outputs/drawn_interactions.h"
#include "deformable_sim/core/outputs/drawn_surfaces.h"
#include "deformable_sim/core/outputs/mesh_catalogue.h"
#include "deformable_sim/core/session/commands.h"
#include "deformable_sim/core/surface_bodies/surface_body.h"
#include "simulation_test_helpers.h"
#include "surface_test_helpers.h"

namespace dc = deformable_sim::core;
namespace dt = deformable_sim::test;

namespace {

dc::BodySpec blockSpec(const std::string& name, bool colour) {
  dc::BodySpec block;
  block.name = name;
  block.box_mesh = dc::BoxMeshSpec{{0, 0, 0}, {0.2, 0.1, 0.1}, {4, 2, 2}};
  block.effects = dc::BodyEffects{};
  block.effects->stress_colouring = colour;
  return block;
}

// Every node of body b moved by x -> stretch x + shift.
void deform(dc::Simulation& sim, int b, const Eigen::Matrix3d& stretch,
            const Eigen::Vector3d& shift) {
  dc::Body& body = sim.bodies()[b];
  Eigen::VectorXd x = body.restPositions();
  for (int i = 0; i < body.numNodes(); ++i)
    x.segment<3>(3 * i) = stretch * x.segment<3>(3 * i) + shift;
  body.setState(x, Eigen::VectorXd::Zero(x.size()));
}

std::string refusal(const std::vector<double>& vertices, const std::vector<uint32_t>& triangles) {
  try {
    dc::unflatten(vertices, triangles, "obstacle mesh 'm'");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(DrawnSurfaces, CornersFollowTheBodyAndCarryItsStrain) {
  dc::SceneSpec spec;
  spec.bodies = {blockSpec("coloured", true), blockSpec("plain", false)};
  dc::Simulation sim = dt::boxMeshSimulation(spec);
  const std::vector<dc::Triangle> boundary = dc::extractSurface(sim.bodies()[0].mesh());
  // Stretched 1 % along x and moved: every element's corotated strain is 0.01.
  const Eigen::Matrix3d stretch = Eigen::Vector3d(1.01, 1.0, 1.0).asDiagonal();
  const Eigen::Vector3d shift(0.3, -0.2, 0.5);
  deform(sim, 0, stretch, shift);
  dc::DrawnSurfaces drawn(sim);
  drawn.update(sim.bodies()[0], 0);
  ASSERT_EQ(drawn.corners().size(), 3 * boundary.size());
  ASSERT_EQ(drawn.strains().size(), drawn.corners().size());
  const dc::Mesh& mesh = sim.bodies()[0].mesh();
  for (size_t c = 0; c < drawn.corners().size(); ++c) {
    const Eigen::Vector3d expected = stretch * mesh.positions[boundary[c / 3][c % 3]] + shift;
    EXPECT_LT((drawn.corners()[c] - expected).norm(), 1e-12) << c;
    EXPECT_NEAR(drawn.strains()[c], 0.01, 1e-9) << c;
  }
  // Without stress colouring: corners, no strains.
  drawn.update(sim.bodies()[1], 1);
  EXPECT_TRUE(drawn.strains().empty());
  EXPECT_EQ(drawn.corners().size(), 3 * boundary.size());
}

TEST(DrawnSurfaces, ABodyMadeFromASurfaceIsDrawnWithThatSurface) {
  dc::SceneSpec spec;
  dc::BodySpec ball = blockSpec("ball", true);
  ball.box_mesh.reset();
  spec.bodies = {ball};
  dc::VoxelSettings cells;
  cells.cell_size = 0.02;
  const dc::TriangleMesh sphere = dt::sphereSurface(0.05, Eigen::Vector3d::Zero(), 8, 16);
  dc::Simulation sim = dt::surfaceSimulation(spec, {dc::bodyFromSurface(sphere, cells, nullptr)});
  Eigen::Matrix3d stretch = Eigen::Vector3d(1.0, 1.0, 0.98).asDiagonal();
  const Eigen::Vector3d shift(0.0, 0.1, 0.2);
  deform(sim, 0, stretch, shift);
  dc::DrawnSurfaces drawn(sim);
  drawn.update(sim.bodies()[0], 0);
  ASSERT_EQ(drawn.corners().size(), 3 * sphere.triangles.size());
  ASSERT_EQ(drawn.strains().size(), drawn.corners().size());
  for (size_t c = 0; c < drawn.corners().size(); ++c) {
    const Eigen::Vector3d expected =
        stretch * sphere.vertices[sphere.triangles[c / 3][c % 3]] + shift;
    EXPECT_LT((drawn.corners()[c] - expected).norm(), 1e-12) << c;
    EXPECT_NEAR(drawn.strains()[c], 0.02, 1e-9) << c;
  }
}

// Fixed at x = 0, grasped at x = 0.1, a group at x = 0.2 (nine nodes each), one pushing wrench and
// one pure torque; then the whole body moved.
TEST(DrawnInteractions, NodesAreDrawnWhereTheyAreAndEachConstrainedNodeOnce) {
  dc::SceneSpec spec;
  spec.bodies = {blockSpec("block", false)};
  spec.bodies[0].fixed.push_back(dt::boxSelection({-1, -1, -1}, {0.001, 1, 1}));
  spec.bodies[0].groups["tip"] = dt::boxSelection({0.199, -1, -1}, {1, 1, 1});
  dc::Simulation sim = dt::boxMeshSimulation(spec);
  dc::CommandProcessor commands(sim);
  dc::GraspCommand grasp;
  grasp.name = "hand";
  grasp.nodes.box = dc::Box{{0.099, -1, -1}, {0.101, 1, 1}};
  ASSERT_EQ(commands.apply(grasp), 9);
  dc::WrenchCommand push;
  push.source = "push";
  push.nodes.group = "tip";
  push.force = Eigen::Vector3d(0, 0, -2);
  push.point = Eigen::Vector3d(0.2, 0.05, 0.05);
  commands.apply(push);
  dc::WrenchCommand twist = push;
  twist.source = "twist";
  twist.force.setZero();
  twist.torque = Eigen::Vector3d(0, 0, 1);
  commands.apply(twist);
  const Eigen::Vector3d shift(0.3, -0.2, 0.5);
  deform(sim, 0, Eigen::Matrix3d::Identity(), shift);

  const dc::DrawnInteractions drawn = dc::drawnInteractions(sim.bodies(), commands, 0.1);
  ASSERT_EQ(drawn.bodies.size(), 1u);
  const dc::DrawnNodes& nodes = drawn.bodies[0];
  ASSERT_EQ(nodes.grasped.size(), 9u);
  ASSERT_EQ(nodes.fixed.size(), 9u);  // the grasped nodes are constrained too, not drawn twice
  ASSERT_EQ(nodes.groups.size(), 1u);
  EXPECT_EQ(nodes.groups[0].first, "tip");
  ASSERT_EQ(nodes.groups[0].second.size(), 9u);
  for (const Eigen::Vector3d& p : nodes.grasped) EXPECT_NEAR(p.x(), 0.1 + shift.x(), 1e-12);
  for (const Eigen::Vector3d& p : nodes.fixed) EXPECT_NEAR(p.x(), shift.x(), 1e-12);
  for (const Eigen::Vector3d& p : nodes.groups[0].second) EXPECT_NEAR(p.x(), 0.2 + 0.3, 1e-12);
  ASSERT_EQ(drawn.wrenches.size(), 1u);  // none for the pure torque
  EXPECT_TRUE(drawn.wrenches[0].from.isApprox(*push.point));
  EXPECT_TRUE(drawn.wrenches[0].to.isApprox(Eigen::Vector3d(0.2, 0.05, -0.15)));
}

TEST(TriangleMeshArrays, RoundTripAndRefuseWhatDoesNotFit) {
  const dc::TriangleMesh box = dc::boxSurface({0, 0, 0}, {1, 2, 3});
  std::vector<double> vertices;
  std::vector<uint32_t> triangles;
  dc::flatten(box, vertices, triangles);
  EXPECT_EQ(vertices.size(), 24u);
  const dc::TriangleMesh back = dc::unflatten(vertices, triangles, "box");
  EXPECT_EQ(back.vertices, box.vertices);
  EXPECT_EQ(back.triangles, box.triangles);
  std::vector<double> short_vertices(vertices.begin(), vertices.end() - 1);
  EXPECT_EQ(refusal(short_vertices, triangles),
            "obstacle mesh 'm': its vertices and triangles must come in threes");
  triangles[4] = 8;
  EXPECT_EQ(refusal(vertices, triangles), "obstacle mesh 'm': a triangle refers to vertex 8 of 8");
}

TEST(MeshCatalogue, ListsAMeshUntilItIsRecordedThenNamesItById) {
  const auto box =
      std::make_shared<const dc::TriangleMeshShape>(dc::boxSurface({0, 0, 0}, {0.1, 0.1, 0.1}));
  const auto ramp =
      std::make_shared<const dc::TriangleMeshShape>(dc::boxSurface({0, 0, 0}, {0.3, 0.1, 0.01}));
  dc::MeshCatalogue catalogue;
  catalogue.addRecorded("mesh0", ramp);  // the scene's record took the first generated id
  std::vector<dc::MeshCatalogue::Entry> unrecorded;
  EXPECT_EQ(catalogue.idFor(ramp, unrecorded), "mesh0");
  EXPECT_TRUE(unrecorded.empty());
  EXPECT_EQ(catalogue.idFor(box, unrecorded), "mesh1");
  EXPECT_EQ(catalogue.idFor(box, unrecorded), "mesh1");
  ASSERT_EQ(unrecorded.size(), 1u);  // once per message
  EXPECT_EQ(unrecorded[0].mesh, box);
  std::vector<dc::MeshCatalogue::Entry> next;
  catalogue.idFor(box, next);
  EXPECT_EQ(next.size(), 1u);  // not published yet: the next message carries it too
  catalogue.markRecorded("mesh1");
  next.clear();
  catalogue.idFor(box, next);
  EXPECT_TRUE(next.empty());
  EXPECT_EQ(catalogue.find("mesh1"), box);
  // A record read back by its writer keeps the mesh it has under that id.
  catalogue.addRecorded("mesh1", ramp);
  EXPECT_EQ(catalogue.find("mesh1"), box);
  try {
    catalogue.find("mesh7");
    ADD_FAILURE() << "an unknown id was found";
  } catch (const dc::CommandError& e) {
    EXPECT_STREQ(e.what(), "obstacle mesh 'mesh7' was not recorded before its use");
  }
}
