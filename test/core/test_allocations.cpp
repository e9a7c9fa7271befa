// The step must not allocate: every global operator new in this test binary is counted.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <memory>
#include <tuple>

#include "deformable_sim/core/bodies/finite_element_body.h"
#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/elements/selection.h"
#include "deformable_sim/core/geometry/shape.h"
#include "deformable_sim/core/geometry/triangle_mesh_shape.h"
#include "deformable_sim/core/session/commands.h"
#include "deformable_sim/core/session/default_scene.h"
#include "deformable_sim/core/session/simulation.h"
#include "deformable_sim/core/surface_bodies/surface_body.h"
#include "malloc_counter.h"
#include "scene_builder.h"
#include "simulation_test_helpers.h"
#include "surface_test_helpers.h"

namespace dc = deformable_sim::core;

namespace {

// A 0.1 m x 0.1 m beam along x (10 x 2 x 2 boxes unless told) clamped at x = 0.
dc::FiniteElementBody clampedBeam(double length, double young, const dc::BodyEffects& effects,
                                  const dc::SolverSettings& solver,
                                  const Eigen::Vector3i& cells = Eigen::Vector3i(10, 2, 2)) {
  dc::FiniteElementBody body("beam",
                             dc::makeBoxMesh({0, -0.05, -0.05}, {length, 0.05, 0.05}, cells),
                             {young, 0.3, 1000}, effects, solver);
  dc::NodeSelection clamp;
  clamp.kind = dc::NodeSelection::Kind::kBox;
  clamp.box = {{-1e-9, -1, -1}, {1e-9, 1, 1}};
  body.fixNodes(dc::selectNodes(body.mesh(), clamp));
  return body;
}

}  // namespace

TEST(Allocations, NoneInAStepAfterTheFirst) {
  // Sanity check of the counter itself.
  const long start = deformable_sim::test::g_allocations.load();
  static void* volatile sink = nullptr;
  (void)sink;
  std::vector<double> probe(1000 + start % 2);
  sink = probe.data();
  EXPECT_GT(deformable_sim::test::g_allocations.load(), start);
  // The 99-node beam keeps its coarse system dense, the 825-node one sparse.
  for (auto [warping, threads, cells] : {std::tuple{true, 1, Eigen::Vector3i(10, 2, 2)},
                                         std::tuple{false, 1, Eigen::Vector3i(10, 2, 2)},
                                         std::tuple{true, 2, Eigen::Vector3i(10, 2, 2)},
                                         std::tuple{true, 1, Eigen::Vector3i(32, 4, 4)}}) {
    dc::SolverSettings solver;
    solver.threads = threads;
    dc::BodyEffects effects;
    effects.warping = warping;
    effects.gravity = Eigen::Vector3d(0, 0, -9.81);
    effects.damping = dc::RayleighDamping{0.1, 0.01};
    dc::FiniteElementBody body = clampedBeam(1.0, 1e5, effects, solver, cells);
    body.step(0.01);
    const long before = deformable_sim::test::g_allocations.load();
    int iterations = 0;
    for (int s = 0; s < 20; ++s) iterations += body.step(0.01).solve.iterations;
    EXPECT_EQ(deformable_sim::test::g_allocations.load() - before, 0)
        << "warping " << warping << ", threads " << threads << ", " << body.numNodes() << " nodes";
    EXPECT_GT(iterations, 0);  // the steps really solved something
  }
}

// A body made from a surface: partial and incompatible-mode hexahedra step like any cells, and
// its embedded surface follows without allocating.
TEST(Allocations, NoneInStepsOfABodyFromASurfaceNorInItsEmbeddedSurface) {
  dc::VoxelSettings settings;
  settings.longest_side_cells = 6;
  dc::SurfaceBody made = dc::bodyFromSurface(
      deformable_sim::test::sphereSurface(0.05, Eigen::Vector3d::Zero(), 12, 24), settings,
      nullptr);
  dc::BodyEffects effects;
  effects.warping = true;
  effects.gravity = Eigen::Vector3d(0, 0, -9.81);
  dc::FiniteElementBody body("ball", made.voxels.mesh, {1e5, 0.3, 1000}, effects,
                             dc::SolverSettings{});
  dc::NodeSelection bottom;
  bottom.kind = dc::NodeSelection::Kind::kBox;
  bottom.box = {{-1, -1, -1}, {1, 1, -0.04}};
  body.fixNodes(dc::selectNodes(body.mesh(), bottom));
  body.step(0.01);
  made.surface.update(body.positions());
  const long before = deformable_sim::test::g_allocations.load();
  int iterations = 0;
  for (int s = 0; s < 10; ++s) {
    iterations += body.step(0.01).solve.iterations;
    made.surface.update(body.positions());
  }
  EXPECT_EQ(deformable_sim::test::g_allocations.load() - before, 0);
  EXPECT_GT(iterations, 0);
}

// The direct solver refactorizes every step (the warped matrix changes), and the factorization
// preconditioner every few: neither allocates once the pattern is analysed.
TEST(Allocations, NoneInRefactorizations) {
  using Settings = dc::SolverSettings;
  for (auto [method, preconditioner] :
       {std::pair{Settings::Method::kDirect, Settings::Preconditioner::kTwoLevel},
        std::pair{Settings::Method::kConjugateGradient,
                  Settings::Preconditioner::kFactorization}}) {
    dc::SolverSettings solver;
    solver.method = method;
    solver.preconditioner = preconditioner;
    solver.coarse_refresh_interval = 3;
    dc::BodyEffects effects;
    effects.gravity = Eigen::Vector3d(0, 0, -9.81);
    dc::FiniteElementBody body = clampedBeam(1.0, 1e5, effects, solver);
    body.step(0.01);
    const long before = deformable_sim::test::g_allocations.load();
    for (int s = 0; s < 10; ++s) EXPECT_TRUE(body.step(0.01).solve.converged);
    EXPECT_EQ(deformable_sim::test::g_allocations.load() - before, 0)
        << "method " << static_cast<int>(method);
    EXPECT_LT(body.positions().minCoeff(), -0.05 - 1e-4);  // the beam really sagged
  }
}

// Steps solved again with their end rotations, or split because those did not settle, allocate
// nothing either (on one thread and on two).
TEST(Allocations, NoneInStepsSolvedAgainOrSplit) {
  for (int threads : {1, 2}) {
    dc::SolverSettings solver;
    solver.threads = threads;
    dc::BodyEffects effects;
    effects.warping = true;
    dc::FiniteElementBody body = clampedBeam(0.5, 1e6, effects, solver);
    body.step(0.01);
    // A kick of 1e4 times the beam's weight on its free end throws it metres within one step.
    dc::NodeSelection tip;
    tip.kind = dc::NodeSelection::Kind::kBox;
    tip.box = {{0.5 - 1e-9, -1, -1}, {0.5 + 1e-9, 1, 1}};
    const std::vector<int> end = dc::selectNodes(body.mesh(), tip);
    const long before = deformable_sim::test::g_allocations.load();
    for (int i : end) body.externalForces()[3 * i + 1] = 4.9e5 / end.size();
    int solves = 0, splits = 0;
    for (int s = 0; s < 10; ++s) {
      const dc::StepReport report = body.step(0.01);
      solves += report.solves;
      splits += report.splits;
      if (s == 0) body.externalForces().setZero();
    }
    EXPECT_EQ(deformable_sim::test::g_allocations.load() - before, 0) << "threads " << threads;
    EXPECT_GT(solves, 10);
    EXPECT_GT(splits, 0);
  }
}

// A grasp frame moves every tick (the node's grasp timer): moving it and stepping allocate
// nothing after the first tick.
TEST(Allocations, NoneWhenAGraspMovesEveryTick) {
  const dc::SceneSpec spec = dc::defaultScene();
  const dc::BoxMeshSpec& box = *spec.bodies[0].box_mesh;
  dc::Simulation simulation = deformable_sim::test::boxMeshSimulation(spec);
  dc::CommandProcessor commands(simulation);
  dc::GraspCommand grasp;
  grasp.name = "gripper";
  grasp.nodes.box =
      dc::Box{box.max - Eigen::Vector3d(0.05, 1, 1), box.max + Eigen::Vector3d::Ones()};
  grasp.frame.translation() = box.max;
  ASSERT_GT(commands.apply(grasp), 0);
  std::vector<dc::StepReport> reports;
  Eigen::Isometry3d frame = grasp.frame;
  auto tick = [&](int s) {
    frame.translation().z() = box.max.z() + 0.001 * s;  // lift it, a millimetre a tick
    commands.moveGrasp("gripper", frame);
    simulation.step(reports);
  };
  tick(1);
  const long before = deformable_sim::test::g_allocations.load();
  for (int s = 2; s <= 20; ++s) tick(s);
  EXPECT_EQ(deformable_sim::test::g_allocations.load() - before, 0);
  const dc::Body& body = simulation.bodies()[0];
  const int node = commands.grasps().at("gripper").nodes[0];
  EXPECT_NEAR(body.positions()[3 * node + 2] - body.restPositions()[3 * node + 2], 0.02, 1e-9);
}

// Contact with a mesh obstacle queries its tree for every node at every step: from a fixed-size
// stack, without allocating.
TEST(Allocations, NoneInContactWithAMeshObstacle) {
  dc::TriangleMesh grid;  // a 2 m x 2 m table top of 20 x 20 squares, facing up
  const int n = 20;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) grid.vertices.emplace_back(-1.0 + 0.1 * i, -1.0 + 0.1 * j, 0.0);
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      grid.triangles.emplace_back(a, b, c);
      grid.triangles.emplace_back(a, c, d);
    }
  }
  dc::SceneSpec spec =
      deformable_sim::test::SceneBuilder().dt(0.01).gravity(9.81).warped().contact(0.5);
  dc::PlacedShape table;
  table.shape.kind = dc::Shape::Kind::kMesh;
  table.shape.mesh = std::make_shared<const dc::TriangleMeshShape>(grid);
  spec.obstacles.push_back(table);
  dc::BodySpec block;
  block.name = "block";
  block.box_mesh = dc::BoxMeshSpec{{-0.05, -0.05, 0.001}, {0.05, 0.05, 0.101}, {3, 3, 3}};
  block.material = {1.0e5, 0.3, 500.0};
  spec.bodies.push_back(block);
  dc::Simulation sim = deformable_sim::test::boxMeshSimulation(spec);
  std::vector<dc::StepReport> reports;
  for (int s = 0; s < 5; ++s) sim.step(reports);  // it lands: contacts exist from here on
  const long before = deformable_sim::test::g_allocations.load();
  int contacts = 0;
  for (int s = 0; s < 20; ++s) {
    sim.step(reports);
    contacts += reports[0].contacts;
  }
  EXPECT_EQ(deformable_sim::test::g_allocations.load() - before, 0);
  EXPECT_GT(contacts, 0);
}

// Bodies made from a surface touch the floor and each other with their surfaces' vertices, each
// on its cell's nodes: holding, releasing and putting them back allocates nothing either.
TEST(Allocations, NoneInContactOfSurfacesWithAnObstacleAndEachOther) {
  dc::SceneSpec spec = deformable_sim::test::sceneOnAFloor(true);
  dc::VoxelSettings settings;
  settings.longest_side_cells = 6;
  std::vector<dc::SurfaceBody> made;
  for (double z : {0.051, 0.152}) {  // the upper ball 1 mm above the lower one
    dc::BodySpec ball;
    ball.name = "ball" + std::to_string(spec.bodies.size());
    ball.material = {1e5, 0.3, 300};
    spec.bodies.push_back(ball);
    made.push_back(dc::bodyFromSurface(
        deformable_sim::test::sphereSurface(0.05, Eigen::Vector3d(0, 0, z), 12, 24), settings,
        nullptr));
  }
  dc::Simulation sim = deformable_sim::test::surfaceSimulation(spec, std::move(made));
  std::vector<dc::StepReport> reports;
  for (int s = 0; s < 10; ++s) sim.step(reports);  // they land: contacts exist from here on
  ASSERT_GT(reports[1].body_contacts, 0);
  const long before = deformable_sim::test::g_allocations.load();
  int contacts = 0, body_contacts = 0;
  for (int s = 0; s < 20; ++s) {
    sim.step(reports);
    contacts += reports[0].contacts;
    body_contacts += reports[1].body_contacts;
  }
  EXPECT_EQ(deformable_sim::test::g_allocations.load() - before, 0);
  EXPECT_GT(contacts, 0);
  EXPECT_GT(body_contacts, 0);
}

// Contact between bodies of every model and of a body with itself: once the bodies touch, their
// steps allocate nothing either.
TEST(Allocations, NoneInContactBetweenBodies) {
  dc::SceneSpec spec = deformable_sim::test::SceneBuilder()
                           .gravity(9.81)
                           .contact(0.5, true, true)
                           .floor({1, 1, 0.1}, "");
  const dc::BodyModel models[] = {dc::BodyModel::kFiniteElement, dc::BodyModel::kRigid,
                                  dc::BodyModel::kPseudoRigid};
  for (int k = 0; k < 3; ++k) {
    dc::BodySpec body;
    body.name = dc::modelName(models[k]);
    body.model = models[k];
    body.box_mesh = dc::BoxMeshSpec{
        {-0.05, -0.05, 0.101 * k}, {0.05, 0.05, 0.101 * k + 0.1}, Eigen::Vector3i(2, 2, 2)};
    body.material = {1e5, 0.3, 100};
    spec.bodies.push_back(body);
  }
  for (int threads : {1, 2}) {  // on two, the bodies step side by side
    SCOPED_TRACE(threads);
    spec.solver.threads = threads;
    dc::Simulation simulation = deformable_sim::test::boxMeshSimulation(spec);
    std::vector<dc::StepReport> reports;
    for (int s = 0; s < 20; ++s) simulation.step(reports);
    ASSERT_GT(reports[1].body_contacts, 0);
    const long before = deformable_sim::test::g_allocations.load();
    for (int s = 0; s < 20; ++s) simulation.step(reports);
    EXPECT_EQ(deformable_sim::test::g_allocations.load() - before, 0);
    EXPECT_GT(reports[1].body_contacts, 0);
  }
}
