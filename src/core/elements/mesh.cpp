#include "deformable_sim/core/elements/mesh.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "deformable_sim/core/elements/cell.h"

namespace deformable_sim::core {

double signedVolume(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                    const Eigen::Vector3d& d) {
  return (b - a).cross(c - a).dot(d - a) / 6.0;
}

double signedVolume(const std::vector<Eigen::Vector3d>& positions, const Tetrahedron& t) {
  return signedVolume(positions[t[0]], positions[t[1]], positions[t[2]], positions[t[3]]);
}

double shapeQuality(const std::vector<Eigen::Vector3d>& positions, const Tetrahedron& t) {
  double squares = 0.0;
  for (int a = 0; a < 4; ++a) {
    for (int b = a + 1; b < 4; ++b) squares += (positions[t[a]] - positions[t[b]]).squaredNorm();
  }
  const double rms = std::sqrt(squares / 6.0);
  return 6.0 * std::sqrt(2.0) * signedVolume(positions, t) / (rms * rms * rms);
}

std::vector<int> sliverTetrahedra(const Mesh& mesh, double min_quality) {
  std::vector<int> slivers;
  for (int e = 0; e < mesh.numTetrahedra(); ++e) {
    if (shapeQuality(mesh.positions, mesh.tetrahedra[e]) < min_quality) slivers.push_back(e);
  }
  return slivers;
}

double Mesh::cellFraction(size_t c) const {
  if (cell_fractions.empty()) return 1.0;
  double sum = 0.0;
  for (double f : cell_fractions[c]) sum += f;
  return sum / 8.0;
}

double totalVolume(const Mesh& mesh) {
  double volume = 0.0;
  for (const Tetrahedron& t : mesh.tetrahedra) volume += signedVolume(mesh.positions, t);
  for (size_t c = 0; c < mesh.cells.size(); ++c) {
    const Cell& cell = mesh.cells[c];
    volume +=
        computeCellRest(cell.type, cellCorners(cell, mesh.positions), mesh.cellOctants(c)).volume;
  }
  return volume;
}

namespace {

// Each element type's faces as local node lists, counter-clockwise seen from outside (-1 pads
// a triangle).
using LocalFaces = std::vector<std::array<int, 4>>;

const LocalFaces& localFaces(CellType type) {
  static const LocalFaces hexahedron = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                        {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  static const LocalFaces wedge = {
      {0, 2, 1, -1}, {3, 4, 5, -1}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}};
  static const LocalFaces pyramid = {
      {0, 3, 2, 1}, {0, 1, 4, -1}, {1, 2, 4, -1}, {2, 3, 4, -1}, {3, 0, 4, -1}};
  switch (type) {
    case CellType::kWedge:
      return wedge;
    case CellType::kPyramid:
      return pyramid;
    default:
      return hexahedron;
  }
}

}  // namespace

std::vector<Face> extractBoundary(const Mesh& mesh) {
  // For a positively oriented tetrahedron (0,1,2,3) these faces have outward normals.
  static const LocalFaces tetrahedron = {
      {0, 2, 1, -1}, {0, 1, 3, -1}, {1, 2, 3, -1}, {0, 3, 2, -1}};
  // A face shared by two elements is interior; count faces by their sorted nodes.
  std::map<std::array<int, 4>, std::pair<int, Face>> faces;
  auto add = [&](const int* nodes, const LocalFaces& local) {
    for (const auto& f : local) {
      Face face;
      for (int k = 0; k < 4; ++k) face.nodes[k] = f[k] < 0 ? -1 : nodes[f[k]];
      std::array<int, 4> key = face.nodes;
      std::sort(key.begin(), key.end());
      auto [it, inserted] = faces.try_emplace(key, 0, face);
      ++it->second.first;
    }
  };
  for (const Tetrahedron& t : mesh.tetrahedra) add(t.data(), tetrahedron);
  for (const Cell& c : mesh.cells) add(c.nodes.data(), localFaces(c.type));
  std::vector<Face> boundary;
  for (const auto& [key, count_and_face] : faces) {
    if (count_and_face.first == 1) boundary.push_back(count_and_face.second);
  }
  return boundary;
}

std::vector<Triangle> extractSurface(const Mesh& mesh) {
  std::vector<Triangle> surface;
  for (const Face& f : extractBoundary(mesh)) {
    surface.push_back({f.nodes[0], f.nodes[1], f.nodes[2]});
    if (f.size() == 4) surface.push_back({f.nodes[0], f.nodes[2], f.nodes[3]});
  }
  return surface;
}

std::vector<double> lumpedMasses(const Mesh& mesh, double density) {
  std::vector<double> mass(mesh.positions.size(), 0.0);
  for (const Tetrahedron& t : mesh.tetrahedra) {
    const double share = 0.25 * density * std::abs(signedVolume(mesh.positions, t));
    for (int i : t) mass[i] += share;
  }
  for (size_t e = 0; e < mesh.cells.size(); ++e) {
    const Cell& c = mesh.cells[e];
    const CellRest rest =
        computeCellRest(c.type, cellCorners(c, mesh.positions), mesh.cellOctants(e));
    for (int k = 0; k < c.size(); ++k) mass[c.nodes[k]] += density * rest.shape_integrals[k];
  }
  return mass;
}

std::vector<int> nodeIndices(const Mesh& mesh, const std::vector<long>& node_numbers) {
  std::unordered_map<long, int> index_of;
  index_of.reserve(mesh.node_numbers.size());
  for (int i = 0; i < static_cast<int>(mesh.node_numbers.size()); ++i) {
    index_of.emplace(mesh.node_numbers[i], i);
  }
  std::vector<int> indices;
  indices.reserve(node_numbers.size());
  for (long number : node_numbers) {
    auto it = index_of.find(number);
    if (it == index_of.end()) {
      throw std::invalid_argument("node " + std::to_string(number) + " is not a node of the mesh");
    }
    indices.push_back(it->second);
  }
  return indices;
}

std::vector<std::vector<int>> nodeNeighbours(const Mesh& mesh) {
  const int num_nodes = mesh.numNodes();
  std::vector<std::vector<int>> neighbours(num_nodes);
  for (int i = 0; i < num_nodes; ++i) neighbours[i].push_back(i);
  for (const Tetrahedron& t : mesh.tetrahedra) {
    for (int a : t) {
      for (int b : t) neighbours[a].push_back(b);
    }
  }
  for (const Cell& c : mesh.cells) {
    for (int a = 0; a < c.size(); ++a) {
      for (int b = 0; b < c.size(); ++b) neighbours[c.nodes[a]].push_back(c.nodes[b]);
    }
  }
  return neighbours;
}

}  // namespace deformable_sim::core
