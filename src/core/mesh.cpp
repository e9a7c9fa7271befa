#include "deformable_sim/core/mesh.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <unordered_map>

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

double totalVolume(const Mesh& mesh) {
  double volume = 0.0;
  for (const Tetrahedron& t : mesh.tetrahedra) volume += signedVolume(mesh.positions, t);
  return volume;
}

std::vector<Triangle> extractSurface(const Mesh& mesh) {
  // For a positively oriented tetrahedron (0,1,2,3) these faces have outward normals.
  static constexpr int kFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  // A face shared by two tetrahedra is interior; count faces by their sorted node triple.
  std::map<std::array<int, 3>, std::pair<int, Triangle>> faces;
  for (const Tetrahedron& t : mesh.tetrahedra) {
    for (const auto& f : kFaces) {
      Triangle tri{t[f[0]], t[f[1]], t[f[2]]};
      std::array<int, 3> key = tri;
      std::sort(key.begin(), key.end());
      auto [it, inserted] = faces.try_emplace(key, 0, tri);
      ++it->second.first;
    }
  }
  std::vector<Triangle> surface;
  for (const auto& [key, count_and_triangle] : faces) {
    if (count_and_triangle.first == 1) surface.push_back(count_and_triangle.second);
  }
  return surface;
}

std::vector<double> lumpedMasses(const Mesh& mesh, double density) {
  std::vector<double> mass(mesh.positions.size(), 0.0);
  for (const Tetrahedron& t : mesh.tetrahedra) {
    const double share = 0.25 * density * std::abs(signedVolume(mesh.positions, t));
    for (int i : t) mass[i] += share;
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

}  // namespace deformable_sim::core
