// The reference cantilever (../shared/reference: 1 m, 0.1 m square, E = 1 MPa, nu = 0.3, tip
// load 0.025 N) given as a surface turned 30 degrees about its long axis, so that the grid cuts
// its faces: voxelized, it bends as the converged 3D solution. And deformable_sim_mesh on a
// small STL.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>

#include "command_output.h"
#include "deformable_sim/bench/reference_results.h"
#include "deformable_sim/core/surface_bodies/voxelization.h"
#include "deformable_sim/io/mesh_reader.h"
#include "deformable_sim/io/scene_file.h"
#include "surface_test_helpers.h"

namespace dc = deformable_sim::core;
namespace dio = deformable_sim::io;
namespace dt = deformable_sim::test;
namespace fs = std::filesystem;

namespace {

constexpr double kLength = 1.0;     // m
constexpr double kHalfSide = 0.05;  // m
constexpr double kTipLoad = 0.025;  // N, case A of the reference

fs::path scratchDirectory(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / (name + "_" + std::to_string(getpid()));
  fs::create_directories(dir);
  return dir;
}

std::string sceneFor(int cells) {
  return "solver: {method: direct}\n"
         "bodies:\n"
         "  - name: beam\n"
         "    mesh: {surface: beam.stl, cells: " +
         std::to_string(cells) +
         "}\n"
         "    material: {youngs_modulus: 1.0e6, poisson_ratio: 0.3, density: 1000.0}\n"
         "    fixed: [{box: {min: [-0.001, -1, -1], max: [0.001, 1, 1]}}]\n"
         "    loads: [{box: {min: [0.999, -1, -1], max: [1.001, 1, 1]}, total_force: [0, 0, " +
         std::to_string(-kTipLoad) + "]}]\n";
}

using CommandResult = deformable_sim::test::CommandOutput;
using deformable_sim::test::runCommand;

// The number after `label` in the tool's output, or NaN.
double printed(const std::string& output, const std::string& label) {
  const std::regex pattern(label + R"(: ([-+0-9.eE]+))");
  std::smatch match;
  return std::regex_search(output, match, pattern) ? std::stod(match[1]) : NAN;
}

}  // namespace

TEST(EmbeddedCantilever, TurnedAboutItsAxisBendsAsTheConvergedReference) {
  const fs::path dir = scratchDirectory("deformable_sim_embedded_cantilever");
  Eigen::Isometry3d turn = Eigen::Isometry3d::Identity();
  turn.rotate(Eigen::AngleAxisd(M_PI / 6.0, Eigen::Vector3d::UnitX()));
  dt::writeAsciiStl(dt::boxSurface(Eigen::Vector3d(0.0, -kHalfSide, -kHalfSide),
                                   Eigen::Vector3d(kLength, kHalfSide, kHalfSide), turn),
                    (dir / "beam.stl").string());
  std::ofstream(dir / "beam.yaml") << sceneFor(36);
  dc::Simulation sim =
      dio::buildSimulation(dio::readSceneFile((dir / "beam.yaml").string()), nullptr);
  EXPECT_LE(sim.bodies()[0].mesh().cells.size(), 1000u);
  ASSERT_TRUE(sim.solveStatic()[0].converged);
  dc::EmbeddedSurface& surface = *sim.embeddedSurface(0);
  surface.update(sim.bodies()[0].positions());
  // The mean of the tip face's four corners: its area mean, for the (bi)linear field there.
  double sum = 0.0;
  int count = 0;
  for (int v = 0; v < surface.numVertices(); ++v) {
    if (surface.restPositions()[v].x() < kLength - 1e-6) continue;
    sum += surface.positions()[v].z() - surface.restPositions()[v].z();
    ++count;
  }
  ASSERT_EQ(count, 4);
  const deformable_sim::bench::ReferenceResults results(DEFORMABLE_SIM_REFERENCE_DIR
                                                        "/results.csv");
  const double converged = results.value("A", "C3D20R", "hex20_L4", "", "tip_uz_mean_area");
  EXPECT_NEAR(sum / count / converged, 1.0, 0.05) << sum / count << " m against " << converged;
  fs::remove_all(dir);
}

TEST(MeshCommand, VoxelizesASmallStlAndWritesItsGrid) {
  const fs::path dir = scratchDirectory("deformable_sim_mesh_command");
  const dc::TriangleMesh ball = dt::sphereSurface(0.05, Eigen::Vector3d(0.2, 0, 0), 12, 24);
  dt::writeAsciiStl(ball, (dir / "ball.stl").string());
  const std::string msh = (dir / "ball.msh").string();
  const CommandResult run =
      runCommand(std::string(DEFORMABLE_SIM_MESH) + " " + (dir / "ball.stl").string() +
                 " --cell-size 0.02 --out " + msh + " 2>&1");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  // The figures it prints are those of the grid it writes.
  const dio::MeshReadResult grid = dio::readGmsh(msh);
  EXPECT_EQ(printed(run.output, "cells"), static_cast<double>(grid.mesh.cells.size()));
  EXPECT_EQ(printed(run.output, "nodes"), static_cast<double>(grid.mesh.numNodes()));
  EXPECT_NEAR(printed(run.output, "enclosed volume"), dc::enclosedVolume(ball),
              1e-6 * dc::enclosedVolume(ball));
  const double partial = printed(run.output, "mass in partial cells");
  EXPECT_GT(partial, 0.0);
  EXPECT_LT(partial, 1.0);
  EXPECT_GE(printed(run.output, "time"), 0.0);
  // The cells a core voxelization of the same surface keeps, on the same grid.
  dc::VoxelSettings settings;
  settings.cell_size = 0.02;
  EXPECT_EQ(
      grid.mesh.cells.size(),
      dc::voxelize(ball, dc::voxelGridFor(ball, settings), settings.levels).mesh.cells.size());
  fs::remove_all(dir);
}

TEST(MeshCommand, HelpBadArgumentsAndBadFiles) {
  const std::string tool = DEFORMABLE_SIM_MESH;
  const CommandResult help = runCommand(tool + " --help 2>/dev/null");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_EQ(help.output.rfind("usage: deformable_sim_mesh", 0), 0u) << help.output;
  EXPECT_EQ(runCommand(tool + " part.stl 2>&1").exit_code, 2);  // no cell size
  EXPECT_EQ(runCommand(tool + " part.stl --cell-size -1 2>&1").exit_code, 2);
  const CommandResult missing = runCommand(tool + " /nonexistent/part.stl --cells 4 2>&1");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.output.find("/nonexistent/part.stl"), std::string::npos) << missing.output;
}

TEST(RunCommand, WritesTheDisplacementsOfTheEmbeddedSurface) {
  const fs::path dir = scratchDirectory("deformable_sim_surface_out");
  dt::writeAsciiStl(dt::boxSurface(Eigen::Vector3d(0.0, -kHalfSide, -kHalfSide),
                                   Eigen::Vector3d(kLength, kHalfSide, kHalfSide)),
                    (dir / "beam.stl").string());
  std::ofstream(dir / "beam.yaml") << sceneFor(20);
  const std::string csv = (dir / "surface.csv").string();
  const CommandResult run =
      runCommand(std::string(DEFORMABLE_SIM_RUN) + " " + (dir / "beam.yaml").string() +
                 " --static --surface-out " + csv + " 2>&1");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "body,vertex,x0,y0,z0,ux,uy,uz");
  int rows = 0;
  while (std::getline(in, line)) {
    ++rows;
    double x0, uz;
    ASSERT_EQ(std::sscanf(line.c_str(), "beam,%*d,%lf,%*f,%*f,%*f,%*f,%lf", &x0, &uz), 2) << line;
    // The clamped end stays, the tip goes down by about P L^3 / 3 E I = 1 mm.
    if (x0 < 1e-9) {
      EXPECT_NEAR(uz, 0.0, 1e-12) << line;
    } else if (x0 > kLength - 1e-6) {
      EXPECT_NEAR(uz, -1.0e-3, 0.1e-3) << line;
    }
  }
  EXPECT_EQ(rows, 8);  // the box's corners, each once
  fs::remove_all(dir);
}
