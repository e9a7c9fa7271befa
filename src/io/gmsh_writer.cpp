#include "deformable_sim/io/gmsh_writer.h"

#include <fstream>

namespace deformable_sim::io {

namespace {

// Gmsh's element type numbers: 4 tetrahedron, 5 hexahedron, 6 prism (wedge), 7 pyramid.
int gmshType(core::CellType type) {
  switch (type) {
    case core::CellType::kHexahedron:
      return 5;
    case core::CellType::kWedge:
      return 6;
    case core::CellType::kPyramid:
      return 7;
  }
  return 5;
}

}  // namespace

void writeGmsh(const core::Mesh& mesh, std::ostream& out) {
  out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n" << mesh.numNodes() << "\n";
  out.precision(17);
  for (int i = 0; i < mesh.numNodes(); ++i) {
    const Eigen::Vector3d& p = mesh.positions[i];
    out << mesh.node_numbers[i] << " " << p.x() << " " << p.y() << " " << p.z() << "\n";
  }
  out << "$EndNodes\n$Elements\n" << mesh.numElements() << "\n";
  long number = 0;
  // Each element: number, type, two tags (physical and elementary entity), its nodes.
  for (const core::Tetrahedron& t : mesh.tetrahedra) {
    out << ++number << " 4 2 1 1";
    for (int i : t) out << " " << mesh.node_numbers[i];
    out << "\n";
  }
  for (const core::Cell& c : mesh.cells) {
    out << ++number << " " << gmshType(c.type) << " 2 1 1";
    for (int k = 0; k < c.size(); ++k) out << " " << mesh.node_numbers[c.nodes[k]];
    out << "\n";
  }
  out << "$EndElements\n";
}

void writeGmshFile(const core::Mesh& mesh, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write '" + path + "'");
  writeGmsh(mesh, out);
  if (!out) throw std::runtime_error("error writing '" + path + "'");
}

}  // namespace deformable_sim::io
