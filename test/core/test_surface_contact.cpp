// A body made from a surface touches obstacles with that surface, not with the grid of cells
// around it: each grid node outside the surface may go as far into an obstacle as it lies outside
// the surface (core/surface_inset.h).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>

#include "deformable_sim/core/box_mesh.h"
#include "deformable_sim/core/surface_inset.h"
#include "deformable_sim/io/scene_file.h"
#include "surface_test_helpers.h"

namespace dc = deformable_sim::core;
namespace dio = deformable_sim::io;
namespace dt = deformable_sim::test;
namespace fs = std::filesystem;

namespace {

constexpr double kRadius = 0.05;    // m
constexpr double kCellSize = 0.03;  // m: 0.1 m across is 3.3 cells, so the grid stands out

dc::Voxelization voxelizeAt(const dc::TriangleMesh& surface, double cell_size) {
  dc::VoxelSettings settings;
  settings.cell_size = cell_size;
  return dc::voxelize(surface, dc::voxelGridFor(surface, settings), settings.levels);
}

// The simulation of `scene` (YAML) beside a ball surface of kRadius about the origin, ball.stl.
dc::Simulation withBall(const std::string& scene) {
  const fs::path dir =
      fs::temp_directory_path() / ("deformable_sim_surface_contact_" + std::to_string(getpid()));
  fs::create_directories(dir);
  dt::writeAsciiStl(dt::sphereSurface(kRadius, Eigen::Vector3d::Zero(), 12, 24),
                    (dir / "ball.stl").string());
  std::ofstream(dir / "scene.yaml") << scene;
  dc::Simulation sim =
      dio::buildSimulation(dio::readSceneFile((dir / "scene.yaml").string()), nullptr);
  fs::remove_all(dir);
  return sim;
}

// The ball's body entry, its lowest point `drop` above z = 0.
std::string ballBody(double drop) {
  std::ostringstream body;
  body << "  - name: ball\n"
          "    mesh: {surface: ball.stl, cell_size: "
       << kCellSize << ", position: [0.01, 0.02, " << kRadius + drop
       << "]}\n"
          "    material: {youngs_modulus: 5.0e4, poisson_ratio: 0.3, density: 300.0}\n";
  return body.str();
}

const char* kSettling =
    "dt: 0.01\n"
    "effects:\n"
    "  gravity: [0, 0, -9.81]\n"
    "  damping: {mass: 2.0, stiffness: 0.005}\n";

void run(dc::Simulation& sim, double seconds) {
  std::vector<dc::StepReport> reports;
  const int steps = static_cast<int>(seconds / sim.dt());
  for (int s = 0; s < steps; ++s) sim.step(reports);
}

// The lowest point of body b's embedded surface and of its grid, m.
std::pair<double, double> lowest(dc::Simulation& sim, int b) {
  const dc::Body& body = sim.bodies()[b];
  dc::EmbeddedSurface& surface = *sim.embeddedSurface(b);
  surface.update(body.positions());
  double vertex = 1.0, node = 1.0;
  for (const Eigen::Vector3d& v : surface.positions()) vertex = std::min(vertex, v.z());
  for (int i = 0; i < body.numNodes(); ++i) node = std::min(node, body.positions()[3 * i + 2]);
  return {vertex, node};
}

}  // namespace

TEST(SurfaceInset, IsEachOutsideNodesDistanceFromTheSurface) {
  const dc::TriangleMesh ball = dt::sphereSurface(kRadius, Eigen::Vector3d::Zero(), 12, 24);
  const dc::Voxelization voxels = voxelizeAt(ball, kCellSize);
  const std::vector<double> insets = dc::surfaceInsets(voxels.mesh, ball);
  ASSERT_EQ(insets.size(), static_cast<size_t>(voxels.mesh.numNodes()));
  int outside = 0;
  for (int i = 0; i < voxels.mesh.numNodes(); ++i) {
    const double from_centre = voxels.mesh.positions[i].norm();
    // The facets lie inside the sphere by at most r (1 - cos(pi / 12)) = 1.7 mm.
    if (from_centre < kRadius - 2e-3) {
      EXPECT_EQ(insets[i], 0.0) << i;
    } else if (from_centre > kRadius) {
      ++outside;
      EXPECT_NEAR(insets[i], from_centre - kRadius, 2e-3) << i;
    }
    EXPECT_LE(insets[i], std::sqrt(3.0) * kCellSize) << i;
  }
  EXPECT_GT(outside, 0);
}

TEST(SurfaceInset, AnAlignedBoxHasNoneOutside) {
  const Eigen::Vector3d min(-0.1, 0.2, 0.0), max(0.5, 0.4, 0.1);
  const dc::TriangleMesh box = dt::boxSurface(min, max);
  const std::vector<double> insets = dc::surfaceInsets(voxelizeAt(box, 0.05).mesh, box);
  EXPECT_LT(*std::max_element(insets.begin(), insets.end()), 1e-12);  // on it, to rounding
}

// Dropped 2 cm onto a floor, the ball settles with its own lowest point on the floor (the grid's
// lowest nodes 1 cm below it stand in the floor); without the insets it would hover 1 cm up.
TEST(SurfaceContact, ABallRestsOnTheFloorWithItsSurfaceNotItsGrid) {
  dc::Simulation sim =
      withBall(std::string(kSettling) +
               "  contact: {friction: 0.6}\n"
               "obstacles:\n"
               "  - {name: floor, box: {size: [1, 1, 0.1]}, position: [0, 0, -0.05]}\n"
               "bodies:\n" +
               ballBody(0.02));
  run(sim, 2.0);
  const auto [vertex, node] = lowest(sim, 0);
  EXPECT_NEAR(vertex, 0.0, 0.1 * kCellSize);
  EXPECT_LT(node, -0.2 * kCellSize);
  const dc::Body& ball = sim.bodies()[0];
  EXPECT_LT(ball.velocities().lpNorm<Eigen::Infinity>(), 0.01);  // at rest
  // The floor carries the ball's weight.
  double mass = 0.0;
  for (double m : ball.nodalMasses()) mass += m;
  const dc::ContactLoad& floor = sim.obstacleContacts(0)[0];
  EXPECT_NEAR(floor.force.z(), 9.81 * mass, 0.02 * 9.81 * mass);
}
