// Bodies from surfaces: the winding number, the voxel grid's mass and its embedded surface.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "deformable_sim/core/bodies/mass_properties.h"
#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/elements/corotational_elasticity.h"
#include "deformable_sim/core/elements/incompatible_modes.h"
#include "deformable_sim/core/geometry/winding_number.h"
#include "deformable_sim/core/session/simulation.h"
#include "deformable_sim/core/surface_bodies/embedded_surface.h"
#include "deformable_sim/core/surface_bodies/voxelization.h"
#include "surface_test_helpers.h"

namespace dc = deformable_sim::core;
namespace dt = deformable_sim::test;

namespace {

constexpr double kDensity = 1000.0;  // kg/m^3

double meshMass(const dc::Mesh& mesh) {
  double sum = 0.0;
  for (double m : dc::lumpedMasses(mesh, kDensity)) sum += m;
  return sum;
}

dc::Voxelization voxelizeAt(const dc::TriangleMesh& surface, double cell_size) {
  dc::VoxelSettings settings;
  settings.cell_size = cell_size;
  return dc::voxelize(surface, dc::voxelGridFor(surface, settings), settings.levels);
}

// The lumped mass of the voxelized body against density x the volume the triangles enclose.
void expectMassOfEnclosedVolume(const dc::TriangleMesh& surface, double cell_size) {
  const dc::Voxelization voxels = voxelizeAt(surface, cell_size);
  const double expected = kDensity * dc::enclosedVolume(surface);
  ASSERT_GT(expected, 0.0);
  EXPECT_NEAR(meshMass(voxels.mesh) / expected, 1.0, 0.005) << voxels.mesh.cells.size() << " cells";
  EXPECT_NEAR(dc::massProperties(voxels.mesh, kDensity).mass / expected, 1.0, 0.005);
  EXPECT_GT(dc::partialCellMassFraction(voxels.mesh), 0.0);
  EXPECT_EQ(voxels.piece_sizes.size(), 1u);
}

}  // namespace

TEST(WindingNumber, OneInsideZeroOutsideAndTheTreeAgreesWithTheExactSum) {
  const dc::TriangleMesh sphere = dt::sphereSurface(0.1, Eigen::Vector3d(0.3, -0.2, 0.1), 24, 48);
  const dc::WindingNumber winding(sphere);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-0.25, 0.25);
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d q =
        Eigen::Vector3d(0.3, -0.2, 0.1) +
        Eigen::Vector3d(coordinate(random), coordinate(random), coordinate(random));
    const double exact = dc::exactWindingNumber(sphere, q);
    const double distance = (q - Eigen::Vector3d(0.3, -0.2, 0.1)).norm();
    // The polygon lies within 1 % of the radius inside the sphere: keep clear of it.
    if (distance < 0.098) {
      EXPECT_NEAR(exact, 1.0, 1e-9);
    } else if (distance > 0.101) {
      EXPECT_NEAR(exact, 0.0, 1e-9);
    }
    EXPECT_NEAR(winding.at(q), exact, 0.02) << q.transpose();
  }
}

TEST(WindingNumber, AHoleLeavesTheInsideInside) {
  dc::TriangleMesh sphere = dt::sphereSurface(0.1, Eigen::Vector3d::Zero(), 24, 48);
  // Remove a cap of triangles around the north pole: the surface is open.
  const size_t before = sphere.triangles.size();
  std::vector<Eigen::Vector3i> kept;
  for (const Eigen::Vector3i& t : sphere.triangles) {
    if (sphere.vertices[t[0]].z() < 0.095 || sphere.vertices[t[1]].z() < 0.095) kept.push_back(t);
  }
  sphere.triangles = kept;
  ASSERT_LT(sphere.triangles.size(), before);
  EXPECT_GT(dc::exactWindingNumber(sphere, Eigen::Vector3d(0, 0, 0.05)), 0.9);
  EXPECT_LT(dc::exactWindingNumber(sphere, Eigen::Vector3d(0.15, 0, 0)), 0.1);
}

TEST(Voxelization, SphereMassIsDensityTimesEnclosedVolume) {
  expectMassOfEnclosedVolume(dt::sphereSurface(0.1, Eigen::Vector3d(0.01, 0.02, -0.03), 32, 64),
                             0.02);
}

TEST(Voxelization, TorusMassIsDensityTimesEnclosedVolume) {
  expectMassOfEnclosedVolume(dt::torusSurface(0.1, 0.04, 64, 32), 0.015);
}

TEST(Voxelization, TurnedCubeMassIsDensityTimesEnclosedVolume) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.rotate(Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 2, 3).normalized()));
  pose.pretranslate(Eigen::Vector3d(0.013, -0.007, 0.021));
  expectMassOfEnclosedVolume(
      dt::boxSurface(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(0.1), pose), 0.01);
}

TEST(Voxelization, AlignedBoxGivesTheHexahedralBoxMesh) {
  const Eigen::Vector3d min(-0.1, 0.2, 0.0), max(0.5, 0.4, 0.1);
  const dc::Voxelization voxels = voxelizeAt(dt::boxSurface(min, max), 0.05);
  const dc::Mesh box = dc::makeBoxMesh(min, max, {12, 4, 2}, dc::BoxElement::kHexahedron);
  ASSERT_EQ(voxels.mesh.numNodes(), box.numNodes());
  ASSERT_EQ(voxels.mesh.cells.size(), box.cells.size());
  for (int i = 0; i < box.numNodes(); ++i) {
    EXPECT_LT((voxels.mesh.positions[i] - box.positions[i]).norm(), 1e-12) << i;
    EXPECT_EQ(voxels.mesh.node_numbers[i], box.node_numbers[i]);
  }
  for (size_t c = 0; c < box.cells.size(); ++c) {
    EXPECT_EQ(voxels.mesh.cells[c].nodes, box.cells[c].nodes) << c;
    EXPECT_EQ(voxels.mesh.cellFraction(c), 1.0) << c;
  }
}

TEST(Voxelization, ASurfaceThatEnclosesNothingIsAnError) {
  // A single flat square: it has area but no inside.
  dc::TriangleMesh sheet;
  sheet.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  sheet.triangles = {{0, 1, 2}, {0, 2, 3}};
  dc::VoxelSettings settings;
  settings.longest_side_cells = 4;
  EXPECT_THROW(dc::voxelize(sheet, dc::voxelGridFor(sheet, settings), 3), std::invalid_argument);
}

TEST(Voxelization, SeparatePiecesAreCounted) {
  dc::TriangleMesh two = dt::boxSurface(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(0.1));
  const dc::TriangleMesh other =
      dt::boxSurface(Eigen::Vector3d(0.3, 0, 0), Eigen::Vector3d(0.4, 0.1, 0.2));
  for (const Eigen::Vector3i& t : other.triangles) two.triangles.push_back(t.array() + 8);
  two.vertices.insert(two.vertices.end(), other.vertices.begin(), other.vertices.end());
  const dc::Voxelization voxels = voxelizeAt(two, 0.05);
  EXPECT_EQ(voxels.piece_sizes, (std::vector<int>{16, 8}));  // 2 x 2 x 4 and 2 x 2 x 2 cells
}

TEST(EmbeddedSurface, FollowsAnAffineMotionOfTheGridExactly) {
  const dc::TriangleMesh torus = dt::torusSurface(0.1, 0.04, 32, 16);
  const dc::Voxelization voxels = voxelizeAt(torus, 0.02);
  dc::EmbeddedSurface embedded(torus, voxels);
  Eigen::Matrix3d a;
  a << 1.1, 0.2, -0.3, 0.05, 0.9, 0.1, -0.2, 0.3, 1.3;
  const Eigen::Vector3d b(0.4, -0.2, 0.7);
  Eigen::VectorXd x(3 * voxels.mesh.numNodes());
  for (int i = 0; i < voxels.mesh.numNodes(); ++i)
    x.segment<3>(3 * i) = a * voxels.mesh.positions[i] + b;
  embedded.update(x);
  ASSERT_EQ(embedded.numVertices(), static_cast<int>(torus.vertices.size()));
  for (int v = 0; v < embedded.numVertices(); ++v) {
    EXPECT_LT((embedded.positions()[v] - (a * torus.vertices[v] + b)).norm(), 1e-12) << v;
  }
  // Normals turn with the inverse transpose; on a torus each is near the analytic one.
  for (int v = 0; v < embedded.numVertices(); ++v)
    EXPECT_NEAR(embedded.normals()[v].norm(), 1.0, 1e-12);
}

TEST(EmbeddedSurface, EmbeddingInTheGridMeshAloneMovesEveryVertexTheSame) {
  // What a replay does: the grid comes back from a recording without its voxelization. A vertex
  // on a face between cells may land in either; trilinear motion agrees on the face, so under
  // any motion of the grid (here a wavy one) every vertex goes to the same place.
  const dc::TriangleMesh torus = dt::torusSurface(0.1, 0.04, 32, 16);
  const dc::Voxelization voxels = voxelizeAt(torus, 0.02);
  dc::EmbeddedSurface direct(torus, voxels);
  dc::EmbeddedSurface again = dc::embedInGrid(torus, voxels.mesh, "the torus");
  ASSERT_EQ(again.numVertices(), direct.numVertices());
  Eigen::VectorXd x(3 * voxels.mesh.numNodes());
  for (int i = 0; i < voxels.mesh.numNodes(); ++i) {
    const Eigen::Vector3d& p = voxels.mesh.positions[i];
    x.segment<3>(3 * i) = p + 0.01 * (30.0 * p).array().sin().matrix();
  }
  direct.update(x);
  again.update(x);
  for (int v = 0; v < direct.numVertices(); ++v) {
    EXPECT_LT((again.positions()[v] - direct.positions()[v]).norm(), 1e-12) << v;
  }
  const dc::Mesh tetrahedra = dc::makeBoxMesh(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(),
                                              {1, 1, 1}, dc::BoxElement::kTetrahedron);
  try {
    dc::embedInGrid(torus, tetrahedra, "body 'beam'");
    FAIL() << "a tetrahedral mesh is no grid";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("body 'beam' is not a grid"), std::string::npos);
  }
}

TEST(CellFractions, ScaleLumpedMassAndStiffness) {
  dc::Mesh mesh = dc::makeBoxMesh(Eigen::Vector3d::Zero(), Eigen::Vector3d(0.2, 0.1, 0.1),
                                  {2, 1, 1}, dc::BoxElement::kHexahedron);
  const std::vector<double> full = dc::lumpedMasses(mesh, kDensity);
  const dc::LinearElasticMaterial material{1e6, 0.3, kDensity};
  dc::CorotationalElasticity full_elasticity(mesh, material);
  full_elasticity.update(Eigen::VectorXd::Zero(3 * mesh.numNodes()), false);
  dc::OctantFractions quarter;
  quarter.fill(0.25);
  mesh.cell_fractions = {dc::OctantFractions{1, 1, 1, 1, 1, 1, 1, 1}, quarter};
  const std::vector<double> partial = dc::lumpedMasses(mesh, kDensity);
  dc::CorotationalElasticity partial_elasticity(mesh, material);
  partial_elasticity.update(Eigen::VectorXd::Zero(3 * mesh.numNodes()), false);
  // Nodes 0, 3, 6, 9 (x = 0) belong to the full cell only, 2, 5, 8, 11 (x = 0.2) to the other.
  for (int i : {0, 3, 6, 9}) EXPECT_DOUBLE_EQ(partial[i], full[i]);
  for (int i : {2, 5, 8, 11}) EXPECT_DOUBLE_EQ(partial[i], 0.25 * full[i]);
  EXPECT_NEAR(dc::totalVolume(mesh), 0.001 + 0.25 * 0.001, 1e-15);
  const dc::BlockSparseMatrix& k_full = full_elasticity.stiffness();
  const dc::BlockSparseMatrix& k_partial = partial_elasticity.stiffness();
  auto block = [](const dc::BlockSparseMatrix& k, int i, int j) {
    return k.blocks()[k.blockIndex(i, j)];
  };
  EXPECT_TRUE(block(k_partial, 2, 2).isApprox(0.25 * block(k_full, 2, 2), 1e-12));
  EXPECT_TRUE(block(k_partial, 2, 5).isApprox(0.25 * block(k_full, 2, 5), 1e-12));
  EXPECT_TRUE(block(k_partial, 0, 0).isApprox(block(k_full, 0, 0), 1e-12));
}

TEST(CellFractions, AHalfFilledCellWeighsAndResistsOnItsFilledSide) {
  dc::Mesh mesh = dc::makeBoxMesh(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(0.1),
                                  {1, 1, 1}, dc::BoxElement::kHexahedron);
  // Material in the octants with xi1 < 0: the half x < 0.05.
  mesh.cell_fractions = {dc::OctantFractions{1, 0, 1, 0, 1, 0, 1, 0}};
  const std::vector<double> mass = dc::lumpedMasses(mesh, kDensity);
  double sum = 0.0;
  for (double m : mass) sum += m;
  EXPECT_NEAR(sum, 0.5 * kDensity * 1e-3, 1e-15);
  EXPECT_NEAR(dc::massProperties(mesh, kDensity).mass, 0.5 * kDensity * 1e-3, 1e-15);
  EXPECT_LT(dc::massProperties(mesh, kDensity).centre.x(), 0.05);
  for (int low : {0, 2, 4, 6}) EXPECT_GT(mass[low], mass[low + 1]);  // x = 0 against x = 0.1
  dc::CorotationalElasticity elasticity(mesh, {1e6, 0.3, kDensity});
  elasticity.update(Eigen::VectorXd::Zero(3 * mesh.numNodes()), false);
  const dc::BlockSparseMatrix& k = elasticity.stiffness();
  EXPECT_GT(k.blocks()[k.blockIndex(0, 0)].trace(), k.blocks()[k.blockIndex(1, 1)].trace());
}

namespace {

// The energy 1/2 u^T K u of corner displacements u(x) at the corners of `cell`.
template <typename Field>
double energyOf(const Eigen::MatrixXd& k, const dc::CellVectors& corners, Field u) {
  Eigen::VectorXd d(24);
  for (int a = 0; a < 8; ++a) d.segment<3>(3 * a) = u(corners[a]);
  return 0.5 * d.dot(k * d);
}

dc::CellVectors unitCubeCorners(const Eigen::Matrix3d& shape) {
  dc::CellVectors corners;
  for (int a = 0; a < 8; ++a) corners[a] = shape * dc::naturalNode(dc::CellType::kHexahedron, a);
  return corners;
}

}  // namespace

TEST(IncompatibleModes, SymmetricRigidModesFreeAndConstantStrainAsFullIntegration) {
  Eigen::Matrix3d shape;  // a sheared, stretched cube
  shape << 0.05, 0.01, 0.0, 0.0, 0.04, 0.005, 0.002, 0.0, 0.06;
  const dc::CellVectors corners = unitCubeCorners(shape);
  const double lambda = 5.8e5, mu = 3.8e5;
  const Eigen::MatrixXd k = dc::incompatibleModesStiffness(corners, lambda, mu);
  const Eigen::MatrixXd full = dc::cellStiffness(dc::CellType::kHexahedron, corners, lambda, mu);
  EXPECT_LT((k - k.transpose()).norm(), 1e-12 * k.norm());
  const Eigen::Vector3d shift(0.1, -0.2, 0.3), axis(0.3, 0.5, -0.2);
  EXPECT_NEAR(energyOf(k, corners, [&](const Eigen::Vector3d&) { return shift; }), 0.0,
              1e-12 * k.norm());
  EXPECT_NEAR(energyOf(k, corners, [&](const Eigen::Vector3d& x) { return axis.cross(x); }), 0.0,
              1e-12 * k.norm());
  // A homogeneous strain leaves the modes at rest (the patch test): the same energy.
  Eigen::Matrix3d gradient;
  gradient << 0.01, 0.002, -0.003, 0.004, -0.02, 0.001, 0.0, 0.003, 0.015;
  auto affine = [&](const Eigen::Vector3d& x) -> Eigen::Vector3d { return gradient * x; };
  EXPECT_NEAR(energyOf(k, corners, affine), energyOf(full, corners, affine),
              1e-9 * energyOf(full, corners, affine));
  // Bending (u_x = x z): the modes take out the spurious shear of full integration.
  auto bending = [](const Eigen::Vector3d& x) -> Eigen::Vector3d {
    return {x.x() * x.z(), -0.5 * x.x() * x.x(), 0.0};
  };
  EXPECT_LT(energyOf(k, corners, bending), 0.8 * energyOf(full, corners, bending));
  EXPECT_GT(energyOf(k, corners, bending), 0.0);
}

TEST(IncompatibleModes, OnlyWhereEveryOctantHoldsEnoughMaterial) {
  dc::OctantFractions fractions;
  fractions.fill(1.0);
  EXPECT_TRUE(dc::incompatibleModesApply(fractions));
  fractions[5] = dc::kModesMinOctantFraction;
  EXPECT_TRUE(dc::incompatibleModesApply(fractions));
  fractions[5] = 0.5 * dc::kModesMinOctantFraction;
  EXPECT_FALSE(dc::incompatibleModesApply(fractions));
}

// The grid of an aligned box surface and makeBoxMesh's hexahedra (with the same element) are
// one body: the same displacement under the same load.
TEST(Voxelization, AlignedBoxHasTheBoxMeshStaticAnswer) {
  const Eigen::Vector3d min(0.0, -0.05, -0.05), max(1.0, 0.05, 0.05);
  dc::Mesh box = dc::makeBoxMesh(min, max, {20, 2, 2}, dc::BoxElement::kHexahedron);
  box.incompatible_modes = true;
  dc::Voxelization voxels = voxelizeAt(dt::boxSurface(min, max), 0.05);
  dc::SceneSpec spec;
  dc::BodySpec body;
  body.name = "beam";
  body.material = {1e6, 0.3, 1000.0};
  dc::NodeSelection clamp, tip;
  clamp.kind = tip.kind = dc::NodeSelection::Kind::kBox;
  clamp.box = {Eigen::Vector3d(-0.001, -1, -1), Eigen::Vector3d(0.001, 1, 1)};
  tip.box = {Eigen::Vector3d(0.999, -1, -1), Eigen::Vector3d(1.001, 1, 1)};
  body.fixed = {clamp};
  dc::LoadSpec load;
  load.where = tip;
  load.kind = dc::LoadSpec::Kind::kTotalForce;
  load.value = Eigen::Vector3d(0.0, 0.0, -0.025);
  body.loads = {load};
  spec.bodies = {body};
  dc::Simulation from_box(spec, {box});
  dc::Simulation from_surface(spec, {voxels.mesh});
  ASSERT_TRUE(from_box.solveStatic().front().converged);
  ASSERT_TRUE(from_surface.solveStatic().front().converged);
  const Eigen::VectorXd& x_box = from_box.bodies().front().positions();
  const Eigen::VectorXd& x_surface = from_surface.bodies().front().positions();
  ASSERT_EQ(x_box.size(), x_surface.size());
  EXPECT_LT((x_box - x_surface).cwiseAbs().maxCoeff(), 1e-9);
  // And the beam bends: the tip moves down by about P L^3 / 3 E I.
  EXPECT_LT(x_surface.minCoeff(), -0.05 - 0.5e-3);
}

// Real meshes have holes and parts that overlap: the winding number's threshold keeps the inside.
TEST(Voxelization, AHoleOrAnOverlapChangesTheMassLittle) {
  const double r = 0.1;
  const dc::TriangleMesh closed = dt::sphereSurface(r, Eigen::Vector3d::Zero(), 32, 64);
  const double closed_mass = meshMass(voxelizeAt(closed, 0.02).mesh);
  dc::TriangleMesh open = closed;
  open.triangles.clear();
  for (const Eigen::Vector3i& t : closed.triangles) {
    // Leave out the cap above z = 0.95 r: a hole about a third of the radius across.
    if (closed.vertices[t[0]].z() < 0.95 * r || closed.vertices[t[1]].z() < 0.95 * r) {
      open.triangles.push_back(t);
    }
  }
  ASSERT_LT(open.triangles.size(), closed.triangles.size());
  EXPECT_NEAR(meshMass(voxelizeAt(open, 0.02).mesh) / closed_mass, 1.0, 0.005);
  // Two spheres whose centres are a radius apart, one triangle soup: the union, counted once
  // (two spheres minus the lens where they overlap, 5/12 pi r^3).
  dc::TriangleMesh both = closed;
  const dc::TriangleMesh other = dt::sphereSurface(r, Eigen::Vector3d(r, 0, 0), 32, 64);
  const int offset = static_cast<int>(both.vertices.size());
  both.vertices.insert(both.vertices.end(), other.vertices.begin(), other.vertices.end());
  for (const Eigen::Vector3i& t : other.triangles) both.triangles.push_back(t.array() + offset);
  const double polygon_ratio = dc::enclosedVolume(closed) / (4.0 / 3.0 * M_PI * r * r * r);
  const double union_volume = polygon_ratio * (8.0 / 3.0 - 5.0 / 12.0) * M_PI * r * r * r;
  EXPECT_NEAR(meshMass(voxelizeAt(both, 0.02).mesh) / (kDensity * union_volume), 1.0, 0.005);
}

TEST(Voxelization, AnOpenSurfaceEnclosesWhatItsHolesCappedClose) {
  // A 0.1 m box with its top missing: by the divergence theorem alone it would enclose 2/3 of
  // the box (deformable_sim_mesh then said the grid was 50 % too large).
  dc::TriangleMesh open = dt::boxSurface(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(0.1));
  std::vector<Eigen::Vector3i> kept;
  for (const Eigen::Vector3i& t : open.triangles) {
    const bool top = open.vertices[t[0]].z() > 0.05 && open.vertices[t[1]].z() > 0.05 &&
                     open.vertices[t[2]].z() > 0.05;
    if (!top) kept.push_back(t);
  }
  ASSERT_EQ(kept.size(), open.triangles.size() - 2);
  open.triangles = kept;
  const dc::Voxelization voxels = voxelizeAt(open, 0.01);
  EXPECT_NEAR(voxels.enclosed_volume, 1e-3, 1e-12);
  EXPECT_NEAR(dc::totalVolume(voxels.mesh), 1e-3, 1e-9);
}
