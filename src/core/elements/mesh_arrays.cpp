#include "deformable_sim/core/elements/mesh_arrays.h"

#include <stdexcept>

namespace deformable_sim::core {

MeshArrays toArrays(const Mesh& mesh) {
  MeshArrays arrays;
  arrays.node_numbers.assign(mesh.node_numbers.begin(), mesh.node_numbers.end());
  for (const Eigen::Vector3d& p : mesh.positions) {
    arrays.rest_positions.insert(arrays.rest_positions.end(), {p.x(), p.y(), p.z()});
  }
  for (const Tetrahedron& t : mesh.tetrahedra) {
    for (int i : t) arrays.tetrahedra.push_back(static_cast<uint32_t>(i));
  }
  for (const Cell& c : mesh.cells) {
    arrays.cell_types.push_back(static_cast<uint8_t>(c.size()));
    for (int k = 0; k < c.size(); ++k) arrays.cells.push_back(static_cast<uint32_t>(c.nodes[k]));
  }
  for (const OctantFractions& f : mesh.cell_fractions) {
    arrays.cell_fractions.insert(arrays.cell_fractions.end(), f.begin(), f.end());
  }
  arrays.incompatible_modes = mesh.incompatible_modes;
  return arrays;
}

namespace {

int nodeIndex(uint32_t index, size_t nodes, const std::string& what) {
  if (index >= nodes) throw std::invalid_argument(what + " refers to a node out of range");
  return static_cast<int>(index);
}

void readCells(const MeshArrays& arrays, const std::string& what, Mesh& mesh) {
  const size_t n = mesh.positions.size();
  size_t next = 0;
  for (uint8_t size : arrays.cell_types) {
    if (size != 5 && size != 6 && size != 8) {
      throw std::invalid_argument(what + " has a cell of unknown type " + std::to_string(size));
    }
    if (next + size > arrays.cells.size()) {
      throw std::invalid_argument(what + " has arrays of inconsistent sizes");
    }
    Cell cell{static_cast<CellType>(size), {}};
    for (int k = 0; k < size; ++k) cell.nodes[k] = nodeIndex(arrays.cells[next + k], n, what);
    next += size;
    mesh.cells.push_back(cell);
  }
  if (next != arrays.cells.size()) {
    throw std::invalid_argument(what + " has arrays of inconsistent sizes");
  }
}

}  // namespace

Mesh fromArrays(const MeshArrays& arrays, const std::string& what) {
  const size_t n = arrays.node_numbers.size();
  if (arrays.rest_positions.size() != 3 * n || arrays.tetrahedra.size() % 4 != 0) {
    throw std::invalid_argument(what + " has arrays of inconsistent sizes");
  }
  Mesh mesh;
  mesh.node_numbers.assign(arrays.node_numbers.begin(), arrays.node_numbers.end());
  for (size_t i = 0; i < n; ++i) {
    mesh.positions.emplace_back(arrays.rest_positions[3 * i], arrays.rest_positions[3 * i + 1],
                                arrays.rest_positions[3 * i + 2]);
  }
  for (size_t e = 0; e < arrays.tetrahedra.size(); e += 4) {
    Tetrahedron t;
    for (int k = 0; k < 4; ++k) t[k] = nodeIndex(arrays.tetrahedra[e + k], n, what);
    mesh.tetrahedra.push_back(t);
  }
  readCells(arrays, what, mesh);
  if (!arrays.cell_fractions.empty() && arrays.cell_fractions.size() != 8 * mesh.cells.size()) {
    throw std::invalid_argument(what + " has arrays of inconsistent sizes");
  }
  mesh.cell_fractions.resize(arrays.cell_fractions.size() / 8);
  for (size_t c = 0; c < mesh.cell_fractions.size(); ++c) {
    for (int k = 0; k < 8; ++k) mesh.cell_fractions[c][k] = arrays.cell_fractions[8 * c + k];
  }
  mesh.incompatible_modes = arrays.incompatible_modes;
  return mesh;
}

}  // namespace deformable_sim::core
