#include "deformable_sim/core/elements/mesh_pieces.h"

#include "deformable_sim/core/base/disjoint_sets.h"

namespace deformable_sim::core {

namespace {

void join(DisjointSets& sets, const int* nodes, int count) {
  for (int k = 1; k < count; ++k) sets.join(nodes[0], nodes[k]);
}

}  // namespace

std::vector<int> elementPieces(const Mesh& mesh) {
  DisjointSets sets(mesh.numNodes());
  for (const Tetrahedron& t : mesh.tetrahedra) join(sets, t.data(), 4);
  for (const Cell& c : mesh.cells) join(sets, c.nodes.data(), c.size());
  std::vector<int> piece_of_root(mesh.numNodes(), -1);
  std::vector<int> pieces;
  pieces.reserve(mesh.numElements());
  int count = 0;
  auto add = [&](int node) {
    int& piece = piece_of_root[sets.root(node)];
    if (piece < 0) piece = count++;
    pieces.push_back(piece);
  };
  for (const Tetrahedron& t : mesh.tetrahedra) add(t[0]);
  for (const Cell& c : mesh.cells) add(c.nodes[0]);
  return pieces;
}

}  // namespace deformable_sim::core
