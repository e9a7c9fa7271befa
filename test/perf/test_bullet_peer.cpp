// The Bullet peer of the performance benchmark is the same model as the core's body: same mesh,
// masses and clamp, and the same static sag under gravity.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "deformable_sim/core/elements/mesh.h"
#include "deformable_sim/perf/bullet_peer.h"
#include "deformable_sim/perf/cantilever.h"

namespace {

namespace core = deformable_sim::core;
namespace perf = deformable_sim::perf;

const Eigen::Vector3i kCells(16, 4, 4);  // the benchmark's 1 536-tetrahedron mesh

std::vector<int> tipNodes(const core::Mesh& mesh) {
  std::vector<int> nodes;
  for (int i = 0; i < mesh.numNodes(); ++i) {
    if (mesh.positions[i].x() > 0.6 - 1e-9) nodes.push_back(i);
  }
  return nodes;
}

double coreTipSag(const perf::Cantilever& cantilever) {
  core::FiniteElementBody body = perf::makeCantileverBody(cantilever);
  const core::StaticReport report = body.solveStatic({});
  EXPECT_TRUE(report.converged);
  double sum = 0.0;
  const std::vector<int> tip = tipNodes(cantilever.mesh);
  for (int i : tip) sum += body.positions()[3 * i + 2] - cantilever.mesh.positions[i].z();
  return sum / static_cast<double>(tip.size());
}

// Steps the damped peer until the tip's speed is negligible; returns the tip's mean sag.
double bulletTipSag(const perf::Cantilever& cantilever, const perf::BulletPeerSettings& settings) {
  perf::BulletPeer peer(cantilever, settings);
  const std::vector<int> tip = tipNodes(cantilever.mesh);
  double speed = 0.0;
  for (int step = 0; step < 400; ++step) {
    peer.step();
    speed = 0.0;
    for (int i : tip) speed = std::max(speed, peer.velocity(i).norm());
    if (step > 20 && speed < 1e-6) break;
  }
  EXPECT_LT(speed, 1e-6) << "the damped peer did not settle";
  double sum = 0.0;
  for (int i : tip) sum += peer.position(i).z() - cantilever.mesh.positions[i].z();
  return sum / static_cast<double>(tip.size());
}

TEST(BulletPeer, SameNodesTetrahedraAndMass) {
  const perf::Cantilever cantilever = perf::makeCantilever(kCells);
  const perf::BulletPeer peer(cantilever);
  ASSERT_EQ(peer.numNodes(), cantilever.mesh.numNodes());
  EXPECT_EQ(peer.numTetrahedra(), cantilever.mesh.numTetrahedra());
  const std::vector<double> lumped =
      core::lumpedMasses(cantilever.mesh, cantilever.material.density);
  std::vector<bool> clamped(cantilever.mesh.numNodes(), false);
  for (int i : cantilever.clamped) clamped[i] = true;
  for (int i = 0; i < peer.numNodes(); ++i) {
    EXPECT_EQ(peer.position(i), cantilever.mesh.positions[i]) << "node " << i;
    // Clamped: zero inverse mass. Free: the lumped rho V / 4 per corner, not Bullet's density
    // helper (four times that).
    EXPECT_NEAR(peer.mass(i), clamped[i] ? 0.0 : lumped[i], 1e-12 * lumped[i]) << "node " << i;
  }
  const double rho_v = cantilever.material.density * 0.6 * 0.2 * 0.2;
  EXPECT_NEAR(core::totalVolume(cantilever.mesh), 0.6 * 0.2 * 0.2, 1e-12);
  EXPECT_NEAR(peer.builtMass(), rho_v, 1e-9 * rho_v);
}

TEST(BulletPeer, ClampedNodesStayPutWhileTheBeamSwings) {
  const perf::Cantilever cantilever = perf::makeCantilever(kCells);
  perf::BulletPeer peer(cantilever);
  const std::vector<int> tip = tipNodes(cantilever.mesh);
  double lowest = 0.0;
  for (int step = 0; step < 20; ++step) {
    peer.step();
    lowest = std::min(lowest, peer.meanPosition(tip).z());
    for (int i : cantilever.clamped) {
      ASSERT_EQ(peer.position(i), cantilever.mesh.positions[i]) << "node " << i << " step " << step;
      ASSERT_EQ(peer.velocity(i).norm(), 0.0) << "node " << i << " step " << step;
    }
  }
  EXPECT_LT(lowest, -0.05);  // it does swing: past the static sag (about 4.8 cm) within 0.2 s
}

// Both sides are linear tetrahedra on the same mesh under the same lumped gravity.
void expectSagsAgree(perf::BulletElasticity elasticity, int substeps, double tolerance) {
  const perf::Cantilever cantilever = perf::makeCantilever(kCells);
  const double core_sag = coreTipSag(cantilever);
  perf::BulletPeerSettings settings;
  settings.elasticity = elasticity;
  settings.substeps = substeps;
  settings.max_newton_iterations = 1;
  settings.mass_damping = 30.0;  // about critical for the first bending mode (17.8 rad/s)
  const double bullet_sag = bulletTipSag(cantilever, settings);
  EXPECT_LT(core_sag, -0.04);
  EXPECT_NEAR(bullet_sag, core_sag, tolerance * std::abs(core_sag))
      << "Bullet " << bullet_sag << " m, deformable_sim " << core_sag << " m";
  std::printf("sag: Bullet %.9f m, deformable_sim %.9f m, relative difference %.2e\n", bullet_sag,
              core_sag, std::abs(bullet_sag - core_sag) / std::abs(core_sag));
}

// btDeformableLinearElasticityForce is the core's model: linear elasticity in each element's
// rotated frame. What differs is Bullet's rotation (an iterative extraction stopped at 0.01) and
// how far the damped settling went. Measured 1.8e-4 of the sag; tolerance 1e-3.
TEST(BulletPeer, LinearElasticityForceSagMatchesTheCore) {
  expectSagsAgree(perf::BulletElasticity::kLinearElasticityForce, 1, 1e-3);
}

// btDeformableCorotatedForce, P = 2 mu (F - R) + lambda (J - 1) J F^-T, matches the core's
// R (2 mu eps + lambda tr(eps) I), eps = R^T F - I, in the shear term exactly and in the volume
// term to first order in strain (a few percent here), so the sags differ at second order.
// Measured 1.1e-4 of the sag; tolerance 1e-3. 25 Bullet steps per 0.01 s: explicit elasticity.
TEST(BulletPeer, CorotatedForceSagMatchesTheCore) {
  expectSagsAgree(perf::BulletElasticity::kCorotatedForce, 25, 1e-3);
}

}  // namespace
