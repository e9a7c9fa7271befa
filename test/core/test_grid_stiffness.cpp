// Grids from surfaces a regular grid cuts badly (test/core/awkward_surfaces.h) are well posed: the
// assembled stiffness has the six rigid modes as its only zero-energy modes, none once fixed; a
// static solve under gravity converges with reactions equal to the weight; a dynamic step costs
// about as many CG iterations as on a full box grid of as many cells.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "awkward_surfaces.h"
#include "deformable_sim/core/bodies/finite_element_body.h"
#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/elements/corotational_elasticity.h"
#include "deformable_sim/core/surface_bodies/voxelization.h"
#include "deformable_sim/perf/scan_blob.h"

namespace dc = deformable_sim::core;
namespace dt = deformable_sim::test;

namespace {

constexpr double kCell = 0.01;  // m

dc::LinearElasticMaterial material() {
  dc::LinearElasticMaterial m;
  m.youngs_modulus = 1.0e6;
  m.poisson_ratio = 0.3;
  m.density = 1000.0;
  return m;
}

struct AwkwardGrid {
  std::string name;
  dc::Mesh mesh;
  bool compact = true;  ///< not a sheet or a shell
};

dc::Mesh voxelized(const dc::TriangleMesh& surface, const dc::VoxelGrid& grid) {
  return dc::voxelize(surface, grid, dc::VoxelSettings{}.levels).mesh;
}

dc::Mesh voxelized(const dc::TriangleMesh& surface) {
  dc::VoxelSettings settings;
  settings.cell_size = kCell;
  return voxelized(surface, dc::voxelGridFor(surface, settings));
}

// The box [0, 4.5 h]^3 on a grid from the origin: the last layer of cells is half filled, its
// edges a quarter and the far corner's cell one octant.
dc::Mesh cornerInOneOctant() {
  dc::VoxelGrid grid;
  grid.cell_size = kCell;
  grid.cells = Eigen::Vector3i::Constant(5);
  return voxelized(dt::boxSurface(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(4.5 * kCell)),
                   grid);
}

std::vector<AwkwardGrid> awkwardGrids() {
  return {
      {"corner in one octant", cornerInOneOctant()},
      {"shell one cell thick",
       voxelized(dt::sphericalShell(0.04, 0.03, Eigen::Vector3d::Zero(), 24, 48)), false},
      {"saddle", voxelized(dt::thickSaddle(0.045, 12.0, 0.02, 30)), false},
      {"noisy sphere with holes",
       voxelized(dt::noisySphereWithHoles(0.045, Eigen::Vector3d::Zero(), 30, 0.001, 4, 0.008))},
  };
}

// The nodes within `reach` of the lowest node's height.
std::vector<int> nodesNearTheBottom(const dc::Mesh& mesh, double reach) {
  double bottom = mesh.positions.front().z();
  for (const Eigen::Vector3d& p : mesh.positions) bottom = std::min(bottom, p.z());
  std::vector<int> nodes;
  for (int i = 0; i < mesh.numNodes(); ++i) {
    if (mesh.positions[i].z() < bottom + reach) nodes.push_back(i);
  }
  return nodes;
}

Eigen::MatrixXd restStiffness(const dc::Mesh& mesh) {
  dc::CorotationalElasticity elasticity(mesh, material());
  Eigen::VectorXd x0(3 * mesh.numNodes());
  for (int i = 0; i < mesh.numNodes(); ++i) x0.segment<3>(3 * i) = mesh.positions[i];
  elasticity.update(x0, false);
  return elasticity.stiffness().toDense();
}

// Eigenvalues below 1e-9 of the largest: zero-energy modes (the rigid ones sit near 1e-15 of it,
// the softest true deformation of these grids above 1e-6).
int zeroEnergyModes(const Eigen::MatrixXd& k) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(k, Eigen::EigenvaluesOnly);
  const Eigen::VectorXd values = eigen.eigenvalues();
  const double largest = values.cwiseAbs().maxCoeff();
  return static_cast<int>((values.array().abs() < 1e-9 * largest).count());
}

Eigen::MatrixXd withoutNodes(const Eigen::MatrixXd& k, const std::vector<int>& nodes) {
  std::vector<int> kept;
  for (int row = 0; row < k.rows(); ++row) {
    if (!std::binary_search(nodes.begin(), nodes.end(), row / 3)) kept.push_back(row);
  }
  Eigen::MatrixXd free(kept.size(), kept.size());
  for (size_t i = 0; i < kept.size(); ++i) {
    for (size_t j = 0; j < kept.size(); ++j) free(i, j) = k(kept[i], kept[j]);
  }
  return free;
}

// Mean CG iterations over 30 steps of `body` (after its set-up).
double iterationsPerStep(dc::Body& body) {
  constexpr int kSteps = 30;
  int iterations = 0;
  for (int s = 0; s < kSteps; ++s) {
    const dc::StepReport report = body.step(0.01);
    EXPECT_TRUE(report.solve.converged);
    iterations += report.solve.iterations;
  }
  return static_cast<double>(iterations) / kSteps;
}

// A free body set moving with a velocity field that varies over a few cells: every mode is
// excited, so the count measures how well posed the step's matrix is, not how the body moves.
double iterationsFree(const dc::Mesh& mesh) {
  dc::BodyEffects effects;
  effects.warping = true;
  dc::FiniteElementBody body("free", mesh, material(), effects, dc::SolverSettings{});
  Eigen::VectorXd v(3 * body.numNodes());
  for (int i = 0; i < body.numNodes(); ++i) {
    const Eigen::Vector3d& p = mesh.positions[i];
    v.segment<3>(3 * i) << std::sin(40 * p.y()), std::cos(30 * p.z()), std::sin(50 * p.x());
  }
  body.setState(body.positions(), v);
  return iterationsPerStep(body);
}

// The body held by its lowest fifth under gravity that pulls it sideways too, as a user holds
// one: nearly free motions of its cells would grow here and take hundreds of iterations a step.
double iterationsHeld(const dc::Mesh& mesh) {
  dc::BodyEffects effects;
  effects.warping = true;
  effects.gravity = Eigen::Vector3d(5.66, 5.66, -5.66);
  dc::FiniteElementBody body("held", mesh, material(), effects, dc::SolverSettings{});
  double bottom = mesh.positions.front().z(), top = bottom;
  for (const Eigen::Vector3d& p : mesh.positions) {
    bottom = std::min(bottom, p.z());
    top = std::max(top, p.z());
  }
  body.fixNodes(nodesNearTheBottom(mesh, 0.2 * (top - bottom) + 1e-9));
  return iterationsPerStep(body);
}

// A cube of hexahedra (with incompatible modes, as voxel grids have) of about `cells` cells.
dc::Mesh boxGridOf(size_t cells) {
  const int n = std::max(1, static_cast<int>(std::lround(std::cbrt(static_cast<double>(cells)))));
  dc::Mesh box = dc::makeBoxMesh(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(n * kCell),
                                 Eigen::Vector3i::Constant(n), dc::BoxElement::kHexahedron);
  box.incompatible_modes = true;
  return box;
}

}  // namespace

TEST(GridStiffness, OnlyTheRigidModesAreFreeAndNoneOnceFixed) {
  for (const AwkwardGrid& grid : awkwardGrids()) {
    SCOPED_TRACE(grid.name);
    ASSERT_LT(grid.mesh.numNodes(), 900);  // a dense eigen-decomposition
    EXPECT_GT(dc::partialCellMassFraction(grid.mesh), 0.25);
    const Eigen::MatrixXd k = restStiffness(grid.mesh);
    EXPECT_EQ(zeroEnergyModes(k), 6);
    EXPECT_EQ(zeroEnergyModes(withoutNodes(k, nodesNearTheBottom(grid.mesh, 0.5 * kCell))), 0);
  }
}

TEST(GridStiffness, StaticSolveUnderGravityConvergesWithReactionsEqualToTheWeight) {
  const Eigen::Vector3d gravity(0.0, 0.0, -9.81);
  for (const AwkwardGrid& grid : awkwardGrids()) {
    SCOPED_TRACE(grid.name);
    dc::BodyEffects effects;
    effects.warping = true;
    effects.gravity = gravity;
    dc::FiniteElementBody body(grid.name, grid.mesh, material(), effects, dc::SolverSettings{});
    body.fixNodes(nodesNearTheBottom(grid.mesh, 0.5 * kCell));
    const dc::StaticReport report = body.solveStatic(dc::StaticSettings{});
    EXPECT_TRUE(report.converged) << report.iterations << " iterations";
    double mass = 0.0;
    for (double m : body.nodalMasses()) mass += m;
    Eigen::Vector3d reaction = Eigen::Vector3d::Zero();
    for (int i = 0; i < body.numNodes(); ++i) reaction += body.reactionForces().segment<3>(3 * i);
    EXPECT_NEAR(reaction.z() / (mass * gravity.norm()), 1.0, 0.005);
    EXPECT_LT(reaction.head<2>().norm(), 0.005 * mass * gravity.norm());
  }
}

TEST(GridStiffness, StepsCostAboutAsManyIterationsAsABoxGridOfTheSameCells) {
  for (const AwkwardGrid& grid : awkwardGrids()) {
    SCOPED_TRACE(grid.name);
    dc::Mesh uncut = grid.mesh;
    for (dc::OctantFractions& f : uncut.cell_fractions) f.fill(1.0);
    const double cut = iterationsFree(grid.mesh), whole = iterationsFree(uncut);
    EXPECT_LE(cut, 2.0 * whole) << cut << " against " << whole << " iterations a step, free";
    // Held, a sheet or a shell moves more than a cube (it is softer) and its warm starts help
    // less: only compact shapes compare with a cube there.
    if (!grid.compact) continue;
    const double held = iterationsHeld(grid.mesh);
    const double cube = iterationsHeld(boxGridOf(grid.mesh.cells.size()));
    EXPECT_LE(held, 2.0 * cube) << held << " against " << cube << " iterations a step, held";
  }
}

namespace {

// The blob of the voxelization benchmark with `holes` patches of triangles cut out.
dc::TriangleMesh blobWithHoles(int holes) {
  dc::TriangleMesh blob = deformable_sim::perf::makeScanBlob();
  std::vector<Eigen::Vector3i> kept;
  for (const Eigen::Vector3i& t : blob.triangles) {
    const Eigen::Vector3d& p = blob.vertices[t[0]];
    bool in_hole = false;
    for (int h = 0; h < holes; ++h) {
      const double angle = 2.0 * M_PI * h / holes;
      const Eigen::Vector3d direction(std::cos(angle), std::sin(angle), 0.3);
      in_hole = in_hole || p.normalized().dot(direction.normalized()) > 0.995;
    }
    if (!in_hole) kept.push_back(t);
  }
  blob.triangles = kept;
  return blob;
}

// One row of the report: the grid of `surface` at `settings`, its mass against the volume
// `enclosed`, and how its steps and static solve go held by its lowest fifth.
void reportRow(const std::string& name, const dc::TriangleMesh& surface,
               const dc::VoxelSettings& settings, double enclosed) {
  const auto start = std::chrono::steady_clock::now();
  const dc::Mesh mesh = dc::voxelize(surface, dc::voxelGridFor(surface, settings), 3).mesh;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  double mass = 0.0;
  for (double m : dc::lumpedMasses(mesh, material().density)) mass += m;
  dc::Mesh uncut = mesh;
  for (dc::OctantFractions& f : uncut.cell_fractions) f.fill(1.0);
  dc::BodyEffects effects;
  effects.warping = true;
  effects.gravity = Eigen::Vector3d(0, 0, -9.81);
  dc::FiniteElementBody body(name, mesh, material(), effects, dc::SolverSettings{});
  body.fixNodes(nodesNearTheBottom(mesh, 0.5 * kCell));
  const dc::StaticReport statics = body.solveStatic(dc::StaticSettings{});
  std::printf("| %s | %zu | %.0f ms | %+.3f %% | %.0f %% | %.1f | %.1f | %.1f | %s, %d |\n",
              name.c_str(), mesh.cells.size(), 1e3 * seconds,
              100.0 * (mass / (material().density * enclosed) - 1.0),
              100.0 * dc::partialCellMassFraction(mesh), iterationsHeld(mesh),
              iterationsHeld(uncut), iterationsHeld(boxGridOf(mesh.cells.size())),
              statics.converged ? "converges" : "does not converge", statics.iterations);
  std::fflush(stdout);
}

}  // namespace

// The table of doc/physics.md ("Cells a surface cuts"): run with --gtest_also_run_disabled_tests.
TEST(GridStiffness, DISABLED_ReportOnTheObjectsTried) {
  std::printf(
      "| surface | cells | voxelization | mass error | mass in cut cells | CG a step "
      "held | uncut | cube | static (iterations) |\n|---|---|---|---|---|---|---|---|---|\n");
  dc::VoxelSettings at_cell;
  at_cell.cell_size = kCell;
  const dc::TriangleMesh shell = dt::sphericalShell(0.04, 0.03, Eigen::Vector3d::Zero(), 24, 48);
  reportRow("shell one cell thick", shell, at_cell, dc::enclosedVolume(shell));
  const dc::TriangleMesh saddle = dt::thickSaddle(0.045, 12.0, 0.02, 30);
  reportRow("saddle two cells thick", saddle, at_cell, dc::enclosedVolume(saddle));
  const dc::TriangleMesh sheet = dt::thickSaddle(0.06, 10.0, 0.012, 30);
  reportRow("saddle 1.2 cells thick", sheet, at_cell, dc::enclosedVolume(sheet));
  const dc::TriangleMesh noisy =
      dt::noisySphereWithHoles(0.045, Eigen::Vector3d::Zero(), 30, 0.001, 4, 0.008);
  // The same noise without holes (the holes are drawn after it) encloses the reference volume.
  const dc::TriangleMesh closed =
      dt::noisySphereWithHoles(0.045, Eigen::Vector3d::Zero(), 30, 0.001, 0, 0.008);
  reportRow("noisy sphere with 4 holes", noisy, at_cell, dc::enclosedVolume(closed));
  const dc::TriangleMesh blob = deformable_sim::perf::makeScanBlob();
  dc::VoxelSettings coarse;
  coarse.longest_side_cells = 22;
  reportRow("scan-like blob, 69,732 triangles", blob, coarse, dc::enclosedVolume(blob));
  const dc::TriangleMesh holes = blobWithHoles(3);
  reportRow("the blob with 3 holes", holes, coarse, dc::enclosedVolume(blob));
}
