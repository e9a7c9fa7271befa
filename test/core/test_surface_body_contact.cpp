// Bodies made from a surface touch other bodies with that surface, not with the grid it was
// voxelized into, whose boundary stands up to a cell outside it: a ball comes to rest on a soft
// slab on its own surface, and two balls thrown at each other meet surface to surface, momentum
// kept.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "contact_test_helpers.h"
#include "deformable_sim/core/session/simulation.h"
#include "deformable_sim/core/surface_bodies/surface_body.h"
#include "scene_builder.h"
#include "simulation_test_helpers.h"
#include "surface_test_helpers.h"

namespace dc = deformable_sim::core;
namespace dt = deformable_sim::test;

namespace {

/// The embedded surface of body b where the body is now: its vertex positions (3 per vertex)
/// and its triangles.
struct PlacedSurface {
  Eigen::VectorXd x;
  std::vector<dc::Triangle> triangles;
};

PlacedSurface placed(dc::Simulation& sim, int b) {
  dc::EmbeddedSurface& surface = *sim.embeddedSurface(b);
  surface.update(sim.bodies()[b].positions());
  PlacedSurface out;
  out.x.resize(3 * surface.numVertices());
  for (int v = 0; v < surface.numVertices(); ++v) out.x.segment<3>(3 * v) = surface.positions()[v];
  for (const Eigen::Vector3i& t : surface.triangles()) out.triangles.push_back({t[0], t[1], t[2]});
  return out;
}

double meanX(const PlacedSurface& surface) {
  double sum = 0.0;
  for (int v = 0; v < surface.x.size() / 3; ++v) sum += surface.x[3 * v];
  return sum / (surface.x.size() / 3);
}

/// A ball of `radius` about `centre` made from its surface on cells of `cell` m.
dc::SurfaceBody ball(double radius, const Eigen::Vector3d& centre, double cell) {
  dc::VoxelSettings cells;
  cells.cell_size = cell;
  return dc::bodyFromSurface(dt::sphereSurface(radius, centre, 16, 32), cells, nullptr);
}

}  // namespace

TEST(SurfaceBodyContact, ABallRestsOnASoftSlabOnItsSurfaceNotOnItsGrid) {
  dc::SceneSpec spec = dt::SceneBuilder()
                           .dt(0.01)
                           .gravity(9.81)
                           .warped()
                           .damping(2.0, 0.002)
                           .contact(0.5, true)
                           .floor({0.4, 0.4, 0.04});
  dc::BodySpec ball_spec;
  ball_spec.name = "ball";
  ball_spec.material = {3.0e4, 0.3, 150.0};
  dc::BodySpec slab;
  slab.name = "slab";
  slab.box_mesh = dc::BoxMeshSpec{{-0.1, -0.1, 0.0}, {0.1, 0.1, 0.04}, {4, 4, 2}};
  slab.box_mesh->element = dc::BoxElement::kHexahedron;
  slab.material = {3.0e4, 0.3, 150.0};
  spec.bodies = {ball_spec, slab};
  // Its grid of 14 mm cells stands about 5 mm outside the surface; it starts 3 mm above the slab.
  dc::Simulation sim = dt::surfaceSimulation(spec, {ball(0.03, {0.01, 0.005, 0.073}, 0.014)});
  std::vector<dc::StepReport> reports;
  int touching = 0;
  for (int s = 0; s < 200; ++s) {
    sim.step(reports);
    touching += reports[0].body_contacts;
  }
  EXPECT_GT(touching, 0);
  const double tolerance = sim.bodyContact()->tolerance(0, 1);
  const PlacedSurface surface = placed(sim, 0);
  const std::vector<dc::Triangle> slab_surface = dc::extractSurface(sim.bodies()[1].mesh());
  double nearest = std::numeric_limits<double>::infinity();
  for (int v = 0; v < surface.x.size() / 3; ++v) {
    const double d = dt::signedDistanceTo(surface.x.segment<3>(3 * v), sim.bodies()[1].positions(),
                                          slab_surface);
    nearest = std::min(nearest, d);
  }
  // Its surface touches the slab's, within the contact's tolerance either way.
  EXPECT_GT(nearest, -tolerance);
  EXPECT_LT(nearest, tolerance);
  // The slab carries it: it neither sinks nor bounces.
  EXPECT_LT(std::abs(dt::momentum(sim.bodies()[0]).z()), 1e-3 * 0.017);
}

TEST(SurfaceBodyContact, TwoBallsThrownAtEachOtherMeetSurfaceToSurfaceWithMomentumKept) {
  dc::SceneSpec spec = dt::SceneBuilder().dt(0.01).warped().contact(0.5, true).solver(
      dc::SolverSettings::Method::kDirect);  // momentum to round-off
  for (const char* name : {"left", "right"}) {
    dc::BodySpec body;
    body.name = name;
    body.material = {1.0e6, 0.3, 100.0};
    spec.bodies.push_back(body);
  }
  // Radius 10 cm on 4.5 cm cells: the grids stand out by more than a centimetre; 2 cm apart,
  // off-centre by 3 cm.
  dc::Simulation sim = dt::surfaceSimulation(
      spec, {ball(0.1, {-0.11, 0, 0}, 0.045), ball(0.1, {0.11, 0.03, 0.0}, 0.045)});
  for (int b = 0; b < 2; ++b) {
    dc::Body& body = sim.bodies()[b];
    const Eigen::VectorXd v =
        Eigen::Vector3d(b == 0 ? 5.0 : -5.0, 0.0, 0.0).replicate(body.numNodes(), 1);
    body.setState(body.positions(), v);
  }
  const double scale = dt::momentum(sim.bodies()[0]).norm();
  const double tolerance = sim.bodyContact()->tolerance(0, 1);
  std::vector<dc::StepReport> reports;
  int touching = 0;
  double deepest = 0.0, nearest = std::numeric_limits<double>::infinity();
  for (int s = 0; s < 20; ++s) {
    sim.step(reports);
    touching += reports[0].body_contacts;
    ASSERT_LE(dt::totalMomentum(sim.bodies()).norm(), 1e-6 * scale) << "step " << s;
    const PlacedSurface left = placed(sim, 0), right = placed(sim, 1);
    for (int v = 0; v < left.x.size() / 3; ++v) {
      const double d = dt::signedDistanceTo(left.x.segment<3>(3 * v), right.x, right.triangles);
      deepest = std::max(deepest, -d);
      nearest = std::min(nearest, d);
    }
  }
  EXPECT_GT(touching, 0);
  // No vertex of one ended a step inside the other deeper than the tolerance, and they came
  // within it: they met surface to surface (their grids would have stopped them centimetres
  // apart). Then they glance off each other, on their own sides.
  EXPECT_LE(deepest, tolerance);
  EXPECT_LT(nearest, tolerance);
  EXPECT_LT(dt::momentum(sim.bodies()[0]).x(), 0.5 * scale);
  EXPECT_LT(meanX(placed(sim, 0)), meanX(placed(sim, 1)));
}
