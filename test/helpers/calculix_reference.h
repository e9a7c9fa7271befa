// The CalculiX reference cases of test/data/calculix/neo_hookean (README there), read into a
// mesh, its held nodes, its dead nodal loads and CalculiX's displacements at each printed load.
#pragma once

#include <Eigen/Core>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "deformable_sim/core/elements/mesh.h"

namespace deformable_sim::test {

struct CalculixReference {
  core::Mesh mesh;
  std::vector<int> fixed;                           ///< held in all three directions
  Eigen::VectorXd loads;                            ///< the full load, N (3 per node)
  std::map<double, Eigen::VectorXd> displacements;  ///< by load fraction, m (3 per node)
};

/// The rows of a CSV file with a header line, as numbers.
inline std::vector<std::vector<double>> readCsvRows(const std::string& path) {
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

/// Case `name`'s files; node numbers 1.. become indices 0...
inline CalculixReference readCalculixReference(const std::string& name) {
  const std::string base =
      std::string(DEFORMABLE_SIM_SOURCE_DIR) + "/test/data/calculix/neo_hookean/" + name;
  CalculixReference r;
  for (const std::vector<double>& row : readCsvRows(base + "_nodes.csv"))
    r.mesh.positions.emplace_back(row[1], row[2], row[3]);
  const int n = r.mesh.numNodes();
  r.mesh.node_numbers.resize(n);
  for (int i = 0; i < n; ++i) r.mesh.node_numbers[i] = i + 1;
  for (const std::vector<double>& row : readCsvRows(base + "_elements.csv")) {
    if (row.size() == 5) {
      r.mesh.tetrahedra.push_back(
          {int(row[1]) - 1, int(row[2]) - 1, int(row[3]) - 1, int(row[4]) - 1});
    } else {
      core::Cell cell;
      for (int k = 0; k < 8; ++k) cell.nodes[k] = int(row[k + 1]) - 1;
      r.mesh.cells.push_back(cell);
    }
  }
  for (const std::vector<double>& row : readCsvRows(base + "_fixed.csv"))
    r.fixed.push_back(int(row[0]) - 1);
  r.loads = Eigen::VectorXd::Zero(3 * n);
  for (const std::vector<double>& row : readCsvRows(base + "_loads.csv"))
    r.loads.segment<3>(3 * (int(row[0]) - 1)) += Eigen::Vector3d(row[1], row[2], row[3]);
  for (const std::vector<double>& row : readCsvRows(base + "_u.csv")) {
    Eigen::VectorXd& u = r.displacements[row[0]];
    if (u.size() == 0) u = Eigen::VectorXd::Zero(3 * n);
    u.segment<3>(3 * (int(row[1]) - 1)) = Eigen::Vector3d(row[2], row[3], row[4]);
  }
  return r;
}

}  // namespace deformable_sim::test
