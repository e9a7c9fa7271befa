#include "deformable_sim/core/elements/box_mesh.h"

#include <array>
#include <stdexcept>
#include <string>

namespace deformable_sim::core {

namespace {

// One hexahedron per cell; or two wedges (the xy diagonal mirrored from cell to cell, as for the
// tetrahedra); or six pyramids, one on each face with its apex at a node added at the centre.
template <typename NodeIndex>
void addCells(Mesh& mesh, const Eigen::Vector3i& cells, NodeIndex node, BoxElement element) {
  for (int k = 0; k < cells.z(); ++k) {
    for (int j = 0; j < cells.y(); ++j) {
      for (int i = 0; i < cells.x(); ++i) {
        // Gmsh's hexahedron order: the bottom face counter-clockwise seen from above, then the top.
        const std::array<int, 8> hex = {node(i, j, k),
                                        node(i + 1, j, k),
                                        node(i + 1, j + 1, k),
                                        node(i, j + 1, k),
                                        node(i, j, k + 1),
                                        node(i + 1, j, k + 1),
                                        node(i + 1, j + 1, k + 1),
                                        node(i, j + 1, k + 1)};
        if (element == BoxElement::kHexahedron) {
          mesh.cells.push_back({CellType::kHexahedron, hex});
        } else if (element == BoxElement::kWedge) {
          // Triangles (0, 1, 3) and (1, 2, 3), or (0, 1, 2) and (0, 2, 3) in mirrored cells.
          const bool mirrored = (i + j) & 1;
          const int halves[2][3] = {{0, 1, mirrored ? 2 : 3}, {mirrored ? 0 : 1, 2, 3}};
          for (const auto& t : halves) {
            mesh.cells.push_back({CellType::kWedge,
                                  {hex[t[0]], hex[t[1]], hex[t[2]], hex[t[0] + 4], hex[t[1] + 4],
                                   hex[t[2] + 4], 0, 0}});
          }
        } else {
          Eigen::Vector3d centre = Eigen::Vector3d::Zero();
          for (int c : hex) centre += mesh.positions[c] / 8.0;
          mesh.positions.push_back(centre);
          mesh.node_numbers.push_back(static_cast<long>(mesh.positions.size()));
          const int apex = mesh.numNodes() - 1;
          // Each face counter-clockwise seen from inside, where the apex is.
          static constexpr int kFaces[6][4] = {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1},
                                               {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 4, 0}};
          for (const auto& f : kFaces) {
            mesh.cells.push_back(
                {CellType::kPyramid, {hex[f[0]], hex[f[1]], hex[f[2]], hex[f[3]], apex, 0, 0, 0}});
          }
        }
      }
    }
  }
}

}  // namespace

Mesh makeBoxMesh(const Eigen::Vector3d& min, const Eigen::Vector3d& max,
                 const Eigen::Vector3i& cells, BoxElement element) {
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
  if (element != BoxElement::kTetrahedron) {
    addCells(mesh, cells, node, element);
    return mesh;
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
