// Bodies from surfaces: the winding number, the voxel grid's mass and its embedded surface.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "deformable_sim/core/box_mesh.h"
#include "deformable_sim/core/corotational_elasticity.h"
#include "deformable_sim/core/embedded_surface.h"
#include "deformable_sim/core/mass_properties.h"
#include "deformable_sim/core/voxelization.h"
#include "deformable_sim/core/winding_number.h"
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
    EXPECT_EQ(voxels.mesh.cell_fractions[c], 1.0) << c;
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

TEST(CellFractions, ScaleLumpedMassAndStiffness) {
  dc::Mesh mesh = dc::makeBoxMesh(Eigen::Vector3d::Zero(), Eigen::Vector3d(0.2, 0.1, 0.1),
                                  {2, 1, 1}, dc::BoxElement::kHexahedron);
  const std::vector<double> full = dc::lumpedMasses(mesh, kDensity);
  const dc::LinearElasticMaterial material{1e6, 0.3, kDensity};
  dc::CorotationalElasticity full_elasticity(mesh, material);
  full_elasticity.update(Eigen::VectorXd::Zero(3 * mesh.numNodes()), false);
  mesh.cell_fractions = {1.0, 0.25};
  const std::vector<double> partial = dc::lumpedMasses(mesh, kDensity);
  dc::CorotationalElasticity partial_elasticity(mesh, material);
  partial_elasticity.update(Eigen::VectorXd::Zero(3 * mesh.numNodes()), false);
  // Nodes 0, 3, 6, 9 (x = 0) belong to the full cell only, 2, 5, 8, 11 (x = 0.2) to the other.
  for (int i : {0, 3, 6, 9}) EXPECT_DOUBLE_EQ(partial[i], full[i]);
  for (int i : {2, 5, 8, 11}) EXPECT_DOUBLE_EQ(partial[i], 0.25 * full[i]);
  EXPECT_NEAR(dc::totalVolume(mesh), 0.001 + 0.25 * 0.001, 1e-15);
  const dc::BlockSparseMatrix& k_full = full_elasticity.stiffness();
  const dc::BlockSparseMatrix& k_partial = partial_elasticity.stiffness();
  const Eigen::Matrix3d corner_full = k_full.blocks()[k_full.blockIndex(2, 2)];
  EXPECT_TRUE(k_partial.blocks()[k_partial.blockIndex(2, 2)].isApprox(0.25 * corner_full, 1e-12));
  EXPECT_TRUE(k_partial.blocks()[k_partial.blockIndex(0, 0)].isApprox(
      k_full.blocks()[k_full.blockIndex(0, 0)], 1e-12));
}
