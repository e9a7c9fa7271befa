// Neo-Hookean statics against CalculiX 2.20 (*HYPERELASTIC, NEO HOOKE under *STATIC, NLGEOM) on
// the same meshes, supports and dead loads: a cantilever bent until its tip sinks about 40 % of
// its length and a block shortened by 5, 10 and 15 %, in tetrahedra (C3D4) and hexahedra (C3D8),
// nu 0.3 and 0.45. The decks, the script that made them and CalculiX's displacements are in
// test/data/calculix/neo_hookean (README there). At every printed load:
// max |u - u_CalculiX| / max |u_CalculiX| <= 1e-5 (the goal is 1e-4; CalculiX prints seven
// digits, which leave up to 5e-7 of the largest).
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "deformable_sim/core/elements/mesh.h"
#include "deformable_sim/core/materials/hyperelastic_elements.h"
#include "deformable_sim/core/materials/static_equilibrium.h"

namespace dc = deformable_sim::core;

namespace {

const std::string kFolder =
    std::string(DEFORMABLE_SIM_SOURCE_DIR) + "/test/data/calculix/neo_hookean/";

/// The rows of a CSV file with a header line, as numbers.
std::vector<std::vector<double>> readRows(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::vector<std::vector<double>> rows;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::vector<double> row;
    std::stringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

struct Reference {
  dc::Mesh mesh;
  std::vector<int> fixed;
  Eigen::VectorXd loads;
  std::map<double, Eigen::VectorXd> displacements;  ///< by load fraction
};

/// A case's files; node numbers 1.. become indices 0...
Reference readReference(const std::string& name) {
  Reference r;
  for (const std::vector<double>& row : readRows(kFolder + name + "_nodes.csv"))
    r.mesh.positions.emplace_back(row[1], row[2], row[3]);
  const int n = r.mesh.numNodes();
  for (const std::vector<double>& row : readRows(kFolder + name + "_elements.csv")) {
    if (row.size() == 5) {
      r.mesh.tetrahedra.push_back(
          {int(row[1]) - 1, int(row[2]) - 1, int(row[3]) - 1, int(row[4]) - 1});
    } else {
      dc::Cell cell;
      for (int k = 0; k < 8; ++k) cell.nodes[k] = int(row[k + 1]) - 1;
      r.mesh.cells.push_back(cell);
    }
  }
  for (const std::vector<double>& row : readRows(kFolder + name + "_fixed.csv"))
    r.fixed.push_back(int(row[0]) - 1);
  r.loads = Eigen::VectorXd::Zero(3 * n);
  for (const std::vector<double>& row : readRows(kFolder + name + "_loads.csv"))
    r.loads.segment<3>(3 * (int(row[0]) - 1)) += Eigen::Vector3d(row[1], row[2], row[3]);
  for (const std::vector<double>& row : readRows(kFolder + name + "_u.csv")) {
    Eigen::VectorXd& u = r.displacements[row[0]];
    if (u.size() == 0) u = Eigen::VectorXd::Zero(3 * n);
    u.segment<3>(3 * (int(row[1]) - 1)) = Eigen::Vector3d(row[2], row[3], row[4]);
  }
  return r;
}

struct Case {
  const char* name;
  double youngs_modulus, poisson_ratio;
};

class NeoHookeanAgainstCalculix : public ::testing::TestWithParam<Case> {};

TEST_P(NeoHookeanAgainstCalculix, DisplacementsWithinAHundredThousandthOfTheLargest) {
  const Case c = GetParam();
  const Reference reference = readReference(c.name);
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
