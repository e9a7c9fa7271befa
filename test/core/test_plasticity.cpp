// The plasticity effect: a bar pulled past yield and released keeps a permanent set; below yield
// it springs back. Off, nothing of it exists.
#include <gtest/gtest.h>

#include <string>

#include "deformable_sim/core/bodies/finite_element_body.h"
#include "deformable_sim/core/elements/box_mesh.h"

namespace dc = deformable_sim::core;

namespace {

const dc::LinearElasticMaterial kFoam{1.0e5, 0.3, 100.0};

struct PullResult {
  double loaded = 0.0;    // tip's mean x displacement under load, m
  double released = 0.0;  // ... after release and settling, m
  double plastic = 0.0;   // largest plastic strain norm
};

// A 0.5 m bar of 0.1 m x 0.1 m clamped at x = 0, pulled along x with `force` (N) on its tip face
// for 2 s, then released for 3 s. Heavily damped so that both phases settle.
PullResult pull(dc::BoxElement element, double force, bool plastic) {
  dc::BodyEffects effects;
  effects.warping = true;
  effects.damping = dc::RayleighDamping{30.0, 0.0};
  if (plastic) effects.plasticity = dc::PlasticitySettings{0.01, 10.0, 0.1};
  dc::FiniteElementBody body(
      "bar", dc::makeBoxMesh({0, -0.05, -0.05}, {0.5, 0.05, 0.05}, {10, 2, 2}, element), kFoam,
      effects, dc::SolverSettings{});
  std::vector<int> clamp, tip;
  for (int i = 0; i < body.numNodes(); ++i) {
    const double x = body.mesh().positions[i].x();
    if (x < 1e-9) clamp.push_back(i);
    if (x > 0.5 - 1e-9) tip.push_back(i);
  }
  body.fixNodes(clamp);
  auto tip_displacement = [&] {
    double sum = 0.0;
    for (int i : tip) sum += body.positions()[3 * i] - body.mesh().positions[i].x();
    return sum / tip.size();
  };
  for (int i : tip) body.externalForces()[3 * i] = force / tip.size();
  PullResult result;
  for (int s = 0; s < 200; ++s) EXPECT_TRUE(body.step(0.01).solve.converged);
  result.loaded = tip_displacement();
  body.externalForces().setZero();
  for (int s = 0; s < 300; ++s) EXPECT_TRUE(body.step(0.01).solve.converged);
  result.released = tip_displacement();
  if (body.plasticity()) {
    for (const Eigen::Matrix3d& e : body.plasticity()->plasticStrains()) {
      result.plastic = std::max(result.plastic, e.norm());
    }
  }
  return result;
}

class Plasticity : public ::testing::TestWithParam<dc::BoxElement> {};

}  // namespace

TEST_P(Plasticity, PastYieldTheBarKeepsAPermanentSet) {
  // 20 N on 0.01 m^2 is 2 kPa, a strain of 0.02: twice the yield strain. The bar is statically
  // determinate, so the stress stays above yield and the bar flows (perfect plasticity) until the
  // plastic strain reaches its cap, 0.1: about 0.09 axially (the norm also counts the lateral
  // contraction), 0.046 m over the bar.
  const PullResult r = pull(GetParam(), 20.0, true);
  EXPECT_NEAR(r.plastic, 0.1, 1e-12);
  EXPECT_GT(r.loaded, 0.045);
  // Released, the elastic part (0.01 m) springs back and the plastic set stays.
  EXPECT_NEAR(r.released, r.loaded - 0.5 * 0.02, 0.003);
  EXPECT_NEAR(r.released, 0.046, 0.006);
}

TEST_P(Plasticity, BelowYieldTheBarSpringsBack) {
  // 2 N: a strain of about 0.002, a fifth of the yield strain.
  const PullResult r = pull(GetParam(), 2.0, true);
  EXPECT_GT(r.loaded, 5e-4);
  EXPECT_EQ(r.plastic, 0.0);
  EXPECT_LT(std::abs(r.released), 1e-6 * r.loaded);
  // Exactly as without the effect.
  const PullResult elastic = pull(GetParam(), 2.0, false);
  EXPECT_EQ(r.loaded, elastic.loaded);
}

INSTANTIATE_TEST_SUITE_P(Elements, Plasticity,
                         ::testing::Values(dc::BoxElement::kTetrahedron,
                                           dc::BoxElement::kHexahedron));

TEST(PlasticityEffect, OffItDoesNotExistAndBadSettingsAreNamed) {
  dc::FiniteElementBody body("bar", dc::makeBoxMesh({0, 0, 0}, {1, 1, 1}, {1, 1, 1}), kFoam, {},
                             {});
  EXPECT_EQ(body.plasticity(), nullptr);
  dc::BodyEffects effects;
  effects.plasticity = dc::PlasticitySettings{0.01, -1.0, 0.5};
  try {
    dc::FiniteElementBody bad("bar", dc::makeBoxMesh({0, 0, 0}, {1, 1, 1}, {1, 1, 1}), kFoam,
                              effects, {});
    FAIL() << "a negative creep rate was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("body 'bar': plasticity: creep"), std::string::npos)
        << e.what();
  }
}
