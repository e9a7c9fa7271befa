// Hard case of contact between bodies: five soft cubes stacked on a floor for a minute. None
// sinks into another further than the contact's tolerance, the stack stays a stack and comes to
// rest, and its energy (kinetic, elastic and gravitational) never grows once the floor has
// caught the stack's first fall (the cubes start exactly on it and on each other, and fall
// g dt^2 in the first step before anything touches). With node-level corrections by lumped
// masses the stack collapsed within 50 steps; it takes each body's answer within its implicit
// step (core/bodies/implicit_response.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "contact_test_helpers.h"
#include "deformable_sim/core/outputs/contact_pairs.h"
#include "deformable_sim/core/session/simulation.h"
#include "scene_builder.h"
#include "simulation_test_helpers.h"

namespace dc = deformable_sim::core;
using deformable_sim::test::centreOfNodes;

namespace {

constexpr double kGravity = 9.81;
constexpr double kSide = 0.1;
constexpr int kCubes = 5;

double totalEnergy(const dc::Simulation& sim) {
  double energy = 0.0;
  for (const dc::Body& body : sim.bodies()) {
    energy += body.kineticEnergy() + body.elasticEnergy();
    for (int i = 0; i < body.numNodes(); ++i) {
      energy += body.nodalMasses()[i] * kGravity * body.positions()[3 * i + 2];
    }
  }
  return energy;
}

/// Gravity, warping, contact between bodies (mu = 0.5) and a floor whose top is z = 0.
dc::SceneSpec floorScene(double stiffness_damping, dc::SolverSettings::Method method) {
  return deformable_sim::test::SceneBuilder()
      .dt(0.01)
      .gravity(kGravity)
      .warped()
      .damping(1.0, stiffness_damping)
      .contact(0.5, true)
      .solver(method)
      .floor({4.0, 4.0, 0.2});
}

dc::Simulation stackOfCubes(const dc::LinearElasticMaterial& material, int cells,
                            int count = kCubes, int threads = 1) {
  // The direct solver: the answers' solves, quickly.
  dc::SceneSpec spec = floorScene(0.005, dc::SolverSettings::Method::kDirect);
  spec.solver.threads = threads;
  for (int k = 0; k < count; ++k) {
    dc::BodySpec cube;
    cube.name = "cube" + std::to_string(k);
    const Eigen::Vector3d min(-0.5 * kSide, -0.5 * kSide, k * kSide);
    cube.box_mesh = dc::BoxMeshSpec{min, min + Eigen::Vector3d::Constant(kSide),
                                    Eigen::Vector3i::Constant(cells)};
    cube.material = material;
    spec.bodies.push_back(cube);
  }
  return deformable_sim::test::boxMeshSimulation(spec);
}

}  // namespace

TEST(BodyStack, FiveSoftCubesStandForAMinute) {
  dc::Simulation sim = stackOfCubes({1.0e5, 0.3, 100.0}, 2);
  const double tolerance = sim.bodyContact()->tolerance(0, 1);
  const double start = totalEnergy(sim);
  std::vector<dc::StepReport> reports;
  sim.step(reports);
  const double caught = totalEnergy(sim);  // the floor lifted the stack back by its first fall
  double highest = caught;
  for (int s = 2; s <= 6000; ++s) {
    sim.step(reports);
    highest = std::max(highest, totalEnergy(sim));
    if (s < 10 || s % 10 != 0) continue;  // each pair once the first fall is caught
    for (int a = 0; a < kCubes; ++a) {
      for (int b = 0; b < kCubes; ++b) {
        if (a == b) continue;
        ASSERT_LE(deformable_sim::test::deepestInside(sim.bodies()[a], sim.bodies()[b]), tolerance)
            << "cube " << a << " in cube " << b << " at step " << s;
      }
    }
  }
  EXPECT_LE(highest, caught + 1e-9 * std::abs(caught));
  EXPECT_LT(totalEnergy(sim), start);  // it lost what settling released
  double kinetic = 0.0;
  for (const dc::Body& body : sim.bodies()) kinetic += body.kineticEnergy();
  EXPECT_LT(kinetic, 1e-5);           // at rest but for a jitter of a few mm/s
  for (int k = 0; k < kCubes; ++k) {  // still a stack: each cube on the one below
    const Eigen::Vector3d c = centreOfNodes(sim.bodies()[k]);
    EXPECT_LT(c.head<2>().norm(), 0.01 * kSide) << "cube " << k;
    EXPECT_NEAR(c.z(), (k + 0.5) * kSide, 0.02 * kSide) << "cube " << k;  // each sags a little
  }
}

TEST(BodyStack, ContactPairsCarryTheWeightOfWhatRestsOnThem) {
  // Two cubes at rest on the floor: the upper one feels its weight from the lower one, which
  // feels it back, and the floor carries both.
  dc::Simulation sim = stackOfCubes({1.0e5, 0.3, 100.0}, 2, 2);
  std::vector<dc::StepReport> reports;
  for (int s = 0; s < 300; ++s) sim.step(reports);
  std::vector<dc::ContactPair> pairs;
  dc::touchingPairs(sim, pairs);
  const double weight = 100.0 * kSide * kSide * kSide * kGravity;  // of one cube, N
  const auto find = [&](int body, const std::string& other) -> const dc::ContactLoad& {
    for (const dc::ContactPair& p : pairs) {
      if (p.body == body && p.other == other) return p.load;
    }
    ADD_FAILURE() << "no pair of body " << body << " with " << other;
    static const dc::ContactLoad none;
    return none;
  };
  const dc::ContactLoad& upper = find(1, "cube0");
  const dc::ContactLoad& lower = find(0, "cube1");
  const dc::ContactLoad& floor = find(0, "floor");
  EXPECT_NEAR(upper.force.z(), weight, 0.02 * weight);
  EXPECT_LT(upper.force.head<2>().norm(), 0.02 * weight);
  EXPECT_LT((lower.force + upper.force).norm(), 1e-9 * weight);  // equal and opposite
  EXPECT_NEAR(floor.force.z(), 2.0 * weight, 0.02 * weight);
  EXPECT_GT(upper.points, 0);
  EXPECT_NEAR(upper.centre.z(), kSide, 0.05 * kSide);  // where they meet
  for (const dc::ContactPair& p : pairs) EXPECT_NE(p.kind, dc::ContactPair::Kind::kSelf);
}

TEST(BodyStack, BodiesSteppedSideBySideOnTwoThreadsGiveTheSameBits) {
  // Bodies step in parallel until contact couples them; each one's step is the same sum in the
  // same order whatever the thread count.
  dc::Simulation one = stackOfCubes({1.0e5, 0.3, 100.0}, 2, 3, 1);
  dc::Simulation two = stackOfCubes({1.0e5, 0.3, 100.0}, 2, 3, 2);
  std::vector<dc::StepReport> reports_one, reports_two;
  for (int s = 0; s < 50; ++s) {
    one.step(reports_one);
    two.step(reports_two);
  }
  for (int b = 0; b < 3; ++b) {
    EXPECT_EQ(one.bodies()[b].positions(), two.bodies()[b].positions()) << "cube " << b;
    EXPECT_EQ(one.bodies()[b].velocities(), two.bodies()[b].velocities()) << "cube " << b;
    EXPECT_EQ(reports_one[b].body_contacts, reports_two[b].body_contacts);
  }
  EXPECT_GT(reports_two[1].body_contacts, 0);
}

namespace {

/// Blocks side by side in a row on the floor, each face on its neighbour's (the contact
/// benchmark's scene, perf/blocks_on_floor.h, smaller).
dc::Simulation rowOfBlocks(int count, int cells, dc::SolverSettings::Method method) {
  dc::SceneSpec spec = floorScene(0.002, method);
  for (int k = 0; k < count; ++k) {
    dc::BodySpec block;
    block.name = "block" + std::to_string(k);
    const Eigen::Vector3d min(0.08 * k, 0.0, 0.0);
    block.box_mesh = dc::BoxMeshSpec{min, min + Eigen::Vector3d(0.08, 0.08, 0.04),
                                     Eigen::Vector3i(2 * cells, 2 * cells, cells)};
    block.material = {1.0e5, 0.3, 500.0};
    spec.bodies.push_back(block);
  }
  return deformable_sim::test::boxMeshSimulation(spec);
}

}  // namespace

// Faces that coincide from the start, their edges on the floor: a node of one block lies on the
// other's bottom edge, where a point is held all but a sliver of its weight. Moving that sliver
// alone to resolve the contact took impulses of 1e25 N s, and the blocks flew off within two
// steps (and a few centimetres apart with finer meshes).
TEST(BodyStack, BlocksSideBySideOnAFloorStayWhereTheyAre) {
  for (const auto method :
       {dc::SolverSettings::Method::kDirect, dc::SolverSettings::Method::kConjugateGradient}) {
    for (int cells : {1, 2}) {
      dc::Simulation sim = rowOfBlocks(3, cells, method);
      std::vector<Eigen::Vector3d> start;
      for (const dc::Body& body : sim.bodies()) start.push_back(centreOfNodes(body));
      std::vector<dc::StepReport> reports;
      for (int s = 0; s < 100; ++s) sim.step(reports);
      for (size_t b = 0; b < start.size(); ++b) {
        const dc::Body& body = sim.bodies()[b];
        // Each sags under its weight (a fraction of a millimetre) and moves no more.
        EXPECT_LT((centreOfNodes(body) - start[b]).norm(), 1e-3)
            << "block " << b << " cells " << cells;
        EXPECT_LT(body.kineticEnergy(), 1e-8) << "block " << b << " cells " << cells;
      }
    }
  }
}

// A body keeps its answers to impulses while its step's matrix stands
// (core/bodies/implicit_response.h): a pile at rest solves for the nodes it first touched with,
// and then for nothing.
TEST(BodyStack, APileAtRestSolvesForItsAnswersOnlyWhenItFirstTouches) {
  for (const auto method :
       {dc::SolverSettings::Method::kDirect, dc::SolverSettings::Method::kConjugateGradient}) {
    dc::Simulation sim = rowOfBlocks(3, 2, method);
    std::vector<dc::StepReport> reports;
    int first = 0, later = 0;
    for (int s = 0; s < 200; ++s) {
      sim.step(reports);
      for (const dc::StepReport& r : reports) (s < 5 ? first : later) += r.body_contact_solves;
    }
    EXPECT_GT(first, 0);
    EXPECT_EQ(later, 0);
  }
}
