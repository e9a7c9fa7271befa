#include "deformable_sim/core/mesh_pieces.h"

#include <numeric>

namespace deformable_sim::core {

namespace {

// Union-find over the nodes, with path halving.
int root(std::vector<int>& parent, int i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

void join(std::vector<int>& parent, const int* nodes, int count) {
  for (int k = 1; k < count; ++k) parent[root(parent, nodes[k])] = root(parent, nodes[0]);
}

}  // namespace

std::vector<int> elementPieces(const Mesh& mesh) {
  std::vector<int> parent(mesh.numNodes());
  std::iota(parent.begin(), parent.end(), 0);
  for (const Tetrahedron& t : mesh.tetrahedra) join(parent, t.data(), 4);
  for (const Cell& c : mesh.cells) join(parent, c.nodes.data(), c.size());
  std::vector<int> piece_of_root(mesh.numNodes(), -1);
  std::vector<int> pieces;
  pieces.reserve(mesh.numElements());
  int count = 0;
  auto add = [&](int node) {
    int& piece = piece_of_root[root(parent, node)];
    if (piece < 0) piece = count++;
    pieces.push_back(piece);
  };
  for (const Tetrahedron& t : mesh.tetrahedra) add(t[0]);
  for (const Cell& c : mesh.cells) add(c.nodes[0]);
  return pieces;
}

}  // namespace deformable_sim::core
