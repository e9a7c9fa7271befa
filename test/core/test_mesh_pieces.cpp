// The separate pieces of a mesh: what a body made from a surface warns of when a part of it would
// move on its own.
#include <gtest/gtest.h>

#include <vector>

#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/elements/mesh_pieces.h"

namespace dc = deformable_sim::core;

namespace {

/// `a` with the elements of `b` added on nodes of their own (no node shared).
dc::Mesh besides(dc::Mesh a, const dc::Mesh& b) {
  const int offset = a.numNodes();
  a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
  for (long number : b.node_numbers) a.node_numbers.push_back(number + offset);
  for (dc::Tetrahedron t : b.tetrahedra) {
    for (int& node : t) node += offset;
    a.tetrahedra.push_back(t);
  }
  for (dc::Cell c : b.cells) {
    for (int k = 0; k < c.size(); ++k) c.nodes[k] += offset;
    a.cells.push_back(c);
  }
  return a;
}

}  // namespace

TEST(MeshPieces, AConnectedMeshIsOnePiece) {
  for (dc::BoxElement element : {dc::BoxElement::kTetrahedron, dc::BoxElement::kHexahedron,
                                 dc::BoxElement::kWedge, dc::BoxElement::kPyramid}) {
    const dc::Mesh mesh = dc::makeBoxMesh({0, 0, 0}, {0.3, 0.2, 0.1}, {3, 2, 1}, element);
    const std::vector<int> pieces = dc::elementPieces(mesh);
    ASSERT_EQ(pieces.size(), static_cast<size_t>(mesh.numElements()));
    for (int piece : pieces) EXPECT_EQ(piece, 0) << static_cast<int>(element);
  }
}

TEST(MeshPieces, BlocksSharingNoNodeArePiecesNumberedInTheOrderOfTheirFirstElement) {
  const dc::Mesh first = dc::makeBoxMesh({0, 0, 0}, {0.1, 0.1, 0.1}, {1, 1, 1});
  const dc::Mesh second = dc::makeBoxMesh({0.5, 0, 0}, {0.6, 0.1, 0.1}, {1, 1, 2});
  const dc::Mesh mesh = besides(first, second);
  const std::vector<int> pieces = dc::elementPieces(mesh);
  ASSERT_EQ(pieces.size(), static_cast<size_t>(mesh.numElements()));
  for (int e = 0; e < mesh.numElements(); ++e) {
    EXPECT_EQ(pieces[e], e < first.numElements() ? 0 : 1) << e;
  }
}

TEST(MeshPieces, TetrahedraAreNumberedBeforeCellsAndAnElementOnBothJoinsThem) {
  // Hexahedra first in the nodes, tetrahedra after: pieces still count from the tetrahedra.
  const dc::Mesh cells =
      dc::makeBoxMesh({0, 0, 0}, {0.1, 0.1, 0.1}, {1, 1, 1}, dc::BoxElement::kHexahedron);
  const dc::Mesh tetrahedra = dc::makeBoxMesh({0.5, 0, 0}, {0.6, 0.1, 0.1}, {1, 1, 1});
  dc::Mesh mesh = besides(cells, tetrahedra);
  std::vector<int> pieces = dc::elementPieces(mesh);
  ASSERT_EQ(pieces.size(), static_cast<size_t>(mesh.numElements()));
  for (int e = 0; e < mesh.numTetrahedra(); ++e) EXPECT_EQ(pieces[e], 0) << e;
  EXPECT_EQ(pieces.back(), 1);  // the hexahedron
  // A tetrahedron on a node of each joins them into one.
  mesh.tetrahedra.push_back({0, cells.numNodes(), cells.numNodes() + 1, cells.numNodes() + 2});
  pieces = dc::elementPieces(mesh);
  for (int piece : pieces) EXPECT_EQ(piece, 0);
}
