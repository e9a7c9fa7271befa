// Hard case of contact between bodies ([contact]): five soft cubes stacked on a floor for a
// minute. None may sink into another further than the contact's tolerance, the stack must stay a
// stack, and its energy (kinetic, elastic and gravitational) must never grow.
//
// Disabled: it fails today within the first 50 steps (a cube 18 mm inside the one below, the
// stack collapsing). Contact between bodies is resolved after the bodies' implicit steps with
// node-level shifts and impulses, and a node's response there is its lumped mass; in the step
// its neighbours hold it with dt^2 K, a hundred times more for these cubes. So the correction
// compresses the contact layer instead of moving the body, and a resting body is not carried
// (doc/physics.md, "Not handled").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "contact_test_helpers.h"
#include "deformable_sim/core/simulation.h"
#include "simulation_test_helpers.h"

namespace dc = deformable_sim::core;

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

Eigen::Vector3d centreOf(const dc::Body& body) {
  return body.positions().reshaped(3, body.numNodes()).rowwise().mean();
}

dc::Simulation stackOfCubes(const dc::LinearElasticMaterial& material, int cells) {
  dc::SceneSpec spec;
  spec.dt = 0.01;
  spec.effects.gravity = Eigen::Vector3d(0, 0, -kGravity);
  spec.effects.warping = true;
  spec.effects.damping = dc::RayleighDamping{1.0, 0.005};
  spec.contact = dc::ContactSettings{0.5, true, false};
  dc::PlacedShape floor;
  floor.name = "floor";
  floor.shape.size = {1.0, 1.0, 0.1};
  floor.pose.translation() = Eigen::Vector3d(0, 0, -0.05);  // top at z = 0
  spec.obstacles.push_back(floor);
  for (int k = 0; k < kCubes; ++k) {
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

TEST(BodyStack, DISABLED_FiveSoftCubesStandForAMinute) {
  dc::Simulation sim = stackOfCubes({1.0e5, 0.3, 100.0}, 2);
  const double tolerance = sim.bodyContact()->tolerance(0, 1);
  const double start = totalEnergy(sim);
  double highest = start;
  std::vector<dc::StepReport> reports;
  for (int s = 1; s <= 6000; ++s) {
    sim.step(reports);
    highest = std::max(highest, totalEnergy(sim));
    if (s % 50 != 0) continue;
    for (int a = 0; a < kCubes; ++a) {
      for (int b = 0; b < kCubes; ++b) {
        if (a == b) continue;
        ASSERT_LE(deformable_sim::test::deepestInside(sim.bodies()[a], sim.bodies()[b]), tolerance)
            << "cube " << a << " in cube " << b << " at step " << s;
      }
    }
  }
  // It never gained energy (rounding aside); it lost what settling released.
  EXPECT_LE(highest, start + 1e-6 * std::abs(start));
  for (int k = 0; k < kCubes; ++k) {  // still a stack: each cube on the one below
    const Eigen::Vector3d c = centreOf(sim.bodies()[k]);
    EXPECT_LT(c.head<2>().norm(), 0.01 * kSide) << "cube " << k;
    EXPECT_NEAR(c.z(), (k + 0.5) * kSide, 0.05 * kSide) << "cube " << k;
  }
}
