#include "deformable_sim/core/box_mesh.h"

#include <stdexcept>
#include <string>

namespace deformable_sim::core {

Mesh makeBoxMesh(const Eigen::Vector3d& min, const Eigen::Vector3d& max,
                 const Eigen::Vector3i& cells) {
  if (!min.allFinite() || !max.allFinite() || !(min.array() < max.array()).all()) {
    throw std::invalid_argument("box mesh: min must be below max on every axis");
  }
  if ((cells.array() < 1).any()) {
    throw std::invalid_argument("box mesh: needs at least one cell per axis");
  }
  // In long: the product of three ints overflows.
  if (static_cast<long>(cells.x()) * cells.y() * cells.z() > kMaxBoxMeshCells) {
    throw std::invalid_argument("box mesh: more than " + std::to_string(kMaxBoxMeshCells) +
                                " cells");
  }
  const Eigen::Vector3i n = cells.array() + 1;  // nodes per axis
  auto node = [&](int i, int j, int k) { return i + n.x() * (j + n.y() * k); };
  Mesh mesh;
  const Eigen::Vector3d h = (max - min).cwiseQuotient(cells.cast<double>());
  for (int k = 0; k < n.z(); ++k) {
    for (int j = 0; j < n.y(); ++j) {
      for (int i = 0; i < n.x(); ++i) {
        mesh.positions.push_back(min + Eigen::Vector3d(i, j, k).cwiseProduct(h));
        mesh.node_numbers.push_back(static_cast<long>(mesh.positions.size()));
      }
    }
  }
  // Corner c of a cell has offset (c & 1, c >> 1 & 1, c >> 2 & 1). The six tetrahedra share the
  // diagonal 0-7 and walk the paths 0 -> 7 through one edge x, y or z at a time. Cells with an odd
  // index along an axis are mirrored along it: neighbours still share face diagonals (the mesh
  // stays conforming), and the mesh has the box's mirror symmetries, so a symmetric load gives a
  // symmetric response (one diagonal direction everywhere bends a beam sideways under gravity).
  static constexpr int kPaths[6][2] = {{1, 3}, {1, 5}, {2, 3}, {2, 6}, {4, 5}, {4, 6}};
  for (int k = 0; k < cells.z(); ++k) {
    for (int j = 0; j < cells.y(); ++j) {
      for (int i = 0; i < cells.x(); ++i) {
        const int mirror = (i & 1) | (j & 1) << 1 | (k & 1) << 2;
        auto corner = [&](int c) {
          c ^= mirror;
          return node(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2 & 1));
        };
        for (const auto& path : kPaths) {
          Tetrahedron t{corner(0), corner(path[0]), corner(path[1]), corner(7)};
          if (signedVolume(mesh.positions, t) < 0.0) std::swap(t[2], t[3]);
          mesh.tetrahedra.push_back(t);
        }
      }
    }
  }
  return mesh;
}

}  // namespace deformable_sim::core
