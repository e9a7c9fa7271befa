// A finite-element body stepping through the Neo-Hookean law (core/elements/elastic_model.h,
// core/materials/neo_hookean_elasticity.h): its static solve against CalculiX, a step of implicit
// Euler converged by Newton's iterations, the linear law at small strain, and what it refuses.
#include <gtest/gtest.h>

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "calculix_reference.h"
#include "deformable_sim/core/bodies/body.h"
#include "deformable_sim/core/bodies/finite_element_body.h"
#include "deformable_sim/core/elements/box_mesh.h"

namespace dc = deformable_sim::core;
namespace dt = deformable_sim::test;

namespace {

dc::BodySettings settingsFor(dc::ElasticLaw law, double youngs_modulus, double poisson_ratio) {
  dc::BodySettings settings;
  settings.model = dc::BodyModel::kFiniteElement;
  settings.material = {youngs_modulus, poisson_ratio, 100.0, law};
  settings.solver.method = dc::SolverSettings::Method::kDirect;
  return settings;
}

// The body's own quasi-static solve, each iteration linearized at the positions it reached, ends
// where CalculiX's Newton does on the foam block shortened 15 %.
TEST(NeoHookeanBody, StaticSolveMatchesCalculix) {
  const dt::CalculixReference reference = dt::readCalculixReference("block_hex_nu030");
  const auto body =
      dc::makeBody("block", reference.mesh, settingsFor(dc::ElasticLaw::kNeoHookean, 3.0e4, 0.3));
  body->fixNodes(reference.fixed);
  body->externalForces() = reference.loads;
  const dc::StaticReport report = body->solveStatic({10, 200, 1e-12});
  EXPECT_TRUE(report.converged);
  const Eigen::VectorXd& expected = reference.displacements.at(1.0);
  const double off = (body->positions() - body->restPositions() - expected).cwiseAbs().maxCoeff() /
                     expected.cwiseAbs().maxCoeff();
  std::printf("[ measured ] Neo-Hookean body, block at 15 %%: off CalculiX by %.2e\n", off);
  EXPECT_LE(off, 1e-4);
  // The warped stiffness on the same block is off by more: large strain, not rotation.
  const auto warped = dc::makeBody("block", reference.mesh,
                                   settingsFor(dc::ElasticLaw::kWarpedStiffness, 3.0e4, 0.3));
  warped->fixNodes(reference.fixed);
  warped->externalForces() = reference.loads;
  ASSERT_TRUE(warped->solveStatic({10, 200, 1e-12}).converged);
  const double warped_off =
      (warped->positions() - warped->restPositions() - expected).cwiseAbs().maxCoeff() /
      expected.cwiseAbs().maxCoeff();
  std::printf("[ measured ] warped stiffness, same block: off CalculiX by %.2e\n", warped_off);
  EXPECT_GT(warped_off, 100 * off);
}

// A cantilever sagging under gravity: every step converges by Newton's iterations to the law's
// equations, in a few; it comes to rest where the static solve puts it.
TEST(NeoHookeanBody, CantileverStepsConvergeAndSettleOnItsStaticState) {
  dc::BodySettings settings = settingsFor(dc::ElasticLaw::kNeoHookean, 3.0e5, 0.45);
  settings.effects.gravity = Eigen::Vector3d(0, 0, -9.81);
  settings.effects.damping = dc::RayleighDamping{4.0, 0.002};
  const dc::Mesh mesh = dc::makeBoxMesh({0, -0.02, -0.02}, {0.3, 0.02, 0.02}, {12, 2, 2},
                                        dc::BoxElement::kHexahedron);
  std::vector<int> clamp;
  for (int i = 0; i < mesh.numNodes(); ++i) {
    if (mesh.positions[i].x() < 1e-9) clamp.push_back(i);
  }
  const auto body = dc::makeBody("beam", mesh, settings);
  const auto statics = dc::makeBody("beam", mesh, settings);
  body->fixNodes(clamp);
  statics->fixNodes(clamp);
  ASSERT_TRUE(statics->solveStatic({10, 200, 1e-12}).converged);
  int solves = 0, steps = 0, splits = 0;
  for (; steps < 300; ++steps) {
    const dc::StepReport report = body->step(0.01);
    ASSERT_TRUE(body->stateIsFinite()) << steps;
    solves += report.solves;
    splits += report.splits;
  }
  const double sag = (statics->positions() - statics->restPositions()).cwiseAbs().maxCoeff();
  const double gap = (body->positions() - statics->positions()).cwiseAbs().maxCoeff();
  std::printf(
      "[ measured ] sag %.4g m, settled %.3g m from the static state, %.2f Newton "
      "iterations a step, %d splits\n",
      sag, gap, static_cast<double>(solves) / steps, splits);
  EXPECT_GT(sag, 0.01);
  EXPECT_LT(gap, 1e-3 * sag);
  EXPECT_LE(static_cast<double>(solves) / steps, 3.0);
}

// At small strain the two laws are one: a stiff cantilever's sag under its weight agrees.
TEST(NeoHookeanBody, SmallStrainSagsAsTheWarpedStiffness) {
  const dc::Mesh mesh = dc::makeBoxMesh({0, -0.02, -0.02}, {0.3, 0.02, 0.02}, {12, 2, 2},
                                        dc::BoxElement::kTetrahedron);
  std::vector<int> clamp;
  for (int i = 0; i < mesh.numNodes(); ++i) {
    if (mesh.positions[i].x() < 1e-9) clamp.push_back(i);
  }
  Eigen::VectorXd sags[2];
  int k = 0;
  for (const dc::ElasticLaw law : {dc::ElasticLaw::kWarpedStiffness, dc::ElasticLaw::kNeoHookean}) {
    dc::BodySettings settings = settingsFor(law, 1.0e8, 0.3);
    settings.effects.gravity = Eigen::Vector3d(0, 0, -9.81);
    settings.effects.warping = true;
    const auto body = dc::makeBody("beam", mesh, settings);
    body->fixNodes(clamp);
    ASSERT_TRUE(body->solveStatic({1, 200, 1e-10}).converged) << int(law);
    sags[k++] = body->positions() - body->restPositions();
  }
  const double largest = sags[0].cwiseAbs().maxCoeff();
  EXPECT_GT(largest, 1e-7);
  EXPECT_LT((sags[1] - sags[0]).cwiseAbs().maxCoeff(), 1e-3 * largest);
}

TEST(NeoHookeanBody, PlasticityIsRefusedByName) {
  dc::BodySettings settings = settingsFor(dc::ElasticLaw::kNeoHookean, 3.0e4, 0.3);
  settings.effects.plasticity = dc::PlasticitySettings{};
  try {
    dc::makeBody("foam", dc::makeBoxMesh({0, 0, 0}, {0.1, 0.1, 0.1}, {1, 1, 1}), settings);
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("body 'foam'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("Neo-Hookean"), std::string::npos) << e.what();
  }
}

}  // namespace

namespace {

// Live tuning changes E, nu and density, not the law (a tuning message carries none): a stiffer
// block sags half as far under a light load.
TEST(NeoHookeanBody, LiveTuningChangesTheModulusAndKeepsTheLaw) {
  const dt::CalculixReference reference = dt::readCalculixReference("block_hex_nu030");
  const auto body =
      dc::makeBody("block", reference.mesh, settingsFor(dc::ElasticLaw::kNeoHookean, 3.0e4, 0.3));
  body->fixNodes(reference.fixed);
  body->externalForces() = 0.01 * reference.loads;  // small strain: sag in proportion to 1 / E
  ASSERT_TRUE(body->solveStatic({1, 200, 1e-12}).converged);
  const double soft = (body->positions() - body->restPositions()).cwiseAbs().maxCoeff();
  dc::BodyTuning tuning;
  tuning.material = dc::LinearElasticMaterial{6.0e4, 0.3, 100.0};  // law: the default
  body->tune(tuning);
  EXPECT_EQ(body->settings().material.law, dc::ElasticLaw::kNeoHookean);
  ASSERT_TRUE(body->solveStatic({1, 200, 1e-12}).converged);
  const double stiff = (body->positions() - body->restPositions()).cwiseAbs().maxCoeff();
  EXPECT_NEAR(stiff / soft, 0.5, 0.01);
}

}  // namespace
