// Neo-Hookean statics against CalculiX 2.20 (*HYPERELASTIC, NEO HOOKE under *STATIC, NLGEOM) on
// the same meshes, supports and dead loads: a cantilever bent until its tip sinks about 40 % of
// its length and a block shortened by 5, 10 and 15 %, in tetrahedra (C3D4) and hexahedra (C3D8),
// nu 0.3 and 0.45. The decks, the script that made them and CalculiX's displacements are in
// test/data/calculix/neo_hookean (README there). At every printed load:
// max |u - u_CalculiX| / max |u_CalculiX| <= 1e-5 (the goal is 1e-4; CalculiX prints seven
// digits, which leave up to 5e-7 of the largest).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "calculix_reference.h"
#include "deformable_sim/core/materials/hyperelastic_elements.h"
#include "deformable_sim/core/materials/static_equilibrium.h"

namespace dc = deformable_sim::core;

namespace {

struct Case {
  const char* name;
  double youngs_modulus, poisson_ratio;
};

class NeoHookeanAgainstCalculix : public ::testing::TestWithParam<Case> {};

TEST_P(NeoHookeanAgainstCalculix, DisplacementsWithinAHundredThousandthOfTheLargest) {
  const Case c = GetParam();
  const deformable_sim::test::CalculixReference reference =
      deformable_sim::test::readCalculixReference(c.name);
  ASSERT_FALSE(reference.displacements.empty());
  const dc::HyperelasticElements elements(
      reference.mesh, dc::NeoHookean::fromYoungPoisson(c.youngs_modulus, c.poisson_ratio));
  Eigen::VectorXd rest(3 * reference.mesh.numNodes());
  for (int i = 0; i < reference.mesh.numNodes(); ++i)
    rest.segment<3>(3 * i) = reference.mesh.positions[i];
  dc::StaticEquilibrium statics(elements, rest, reference.fixed, reference.loads);
  for (const auto& [fraction, expected] : reference.displacements) {
    const dc::StaticReport report = statics.loadTo(fraction);
    EXPECT_TRUE(report.converged) << c.name << " at " << fraction << ": " << report.residual;
    const double largest = expected.cwiseAbs().maxCoeff();
    const double off = (statics.displacements() - expected).cwiseAbs().maxCoeff() / largest;
    std::printf("%-16s load %.4f  max |u| %.6f m  off %.2e  Newton %d (%d projected)\n", c.name,
                fraction, largest, off, report.iterations, report.projected);
    EXPECT_LE(off, 1e-5) << c.name << " at load fraction " << fraction;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, NeoHookeanAgainstCalculix,
    ::testing::Values(Case{"beam_hex_nu030", 1.0e6, 0.3}, Case{"beam_tet_nu030", 1.0e6, 0.3},
                      Case{"beam_hex_nu045", 1.0e6, 0.45}, Case{"beam_tet_nu045", 1.0e6, 0.45},
                      Case{"block_hex_nu030", 3.0e4, 0.3}, Case{"block_tet_nu030", 3.0e4, 0.3},
                      Case{"block_hex_nu045", 3.0e4, 0.45}, Case{"block_tet_nu045", 3.0e4, 0.45}),
    [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

}  // namespace
