// Grids from surfaces a regular grid cuts badly (test/core/awkward_surfaces.h) are well posed: the
// assembled stiffness has the six rigid modes as its only zero-energy modes, none once fixed; a
// static solve under gravity converges with reactions equal to the weight; a dynamic step costs
// about as many CG iterations as on a full box grid of as many cells.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "awkward_surfaces.h"
#include "deformable_sim/core/body.h"
#include "deformable_sim/core/box_mesh.h"
#include "deformable_sim/core/corotational_elasticity.h"
#include "deformable_sim/core/voxelization.h"

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
  dc::Body body("free", mesh, material(), effects, dc::SolverSettings{});
  Eigen::VectorXd v(3 * body.numNodes());
  for (int i = 0; i < body.numNodes(); ++i) {
    const Eigen::Vector3d& p = mesh.positions[i];
    v.segment<3>(3 * i) << std::sin(40 * p.y()), std::cos(30 * p.z()), std::sin(50 * p.x());
  }
  body.setState(body.positions(), v);
  return iterationsPerStep(body);
}

// The body held by its lowest fifth under gravity that pulls it sideways too: how a user meets
// it (a surface body's nearly free motions, before, grew here and took hundreds of iterations).
double iterationsHeld(const dc::Mesh& mesh) {
  dc::BodyEffects effects;
  effects.warping = true;
  effects.gravity = Eigen::Vector3d(5.66, 5.66, -5.66);
  dc::Body body("held", mesh, material(), effects, dc::SolverSettings{});
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
    dc::Body body(grid.name, grid.mesh, material(), effects, dc::SolverSettings{});
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
