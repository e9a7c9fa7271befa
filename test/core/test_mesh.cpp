#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <map>
#include <string>

#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/elements/loads.h"
#include "deformable_sim/core/elements/mesh.h"
#include "deformable_sim/core/elements/mesh_arrays.h"
#include "deformable_sim/core/elements/selection.h"

namespace dc = deformable_sim::core;

TEST(BoxMesh, CountsVolumesAndOrientation) {
  const dc::Mesh mesh = dc::makeBoxMesh({0, 0, 0}, {1.0, 0.5, 0.25}, {4, 2, 3});
  EXPECT_EQ(mesh.numNodes(), 5 * 3 * 4);
  EXPECT_EQ(mesh.numTetrahedra(), 6 * 4 * 2 * 3);
  for (const dc::Tetrahedron& t : mesh.tetrahedra)
    EXPECT_GT(dc::signedVolume(mesh.positions, t), 0.0);
  EXPECT_NEAR(dc::totalVolume(mesh), 0.125, 1e-15);
  EXPECT_THROW(dc::makeBoxMesh({0, 0, 0}, {1, 1, 1}, {0, 1, 1}), std::invalid_argument);
  // More cells than an int can count nodes for, or than memory holds: refused, not attempted.
  EXPECT_THROW(dc::makeBoxMesh({0, 0, 0}, {1, 1, 1}, {2000, 2000, 2000}), std::invalid_argument);
  EXPECT_THROW(dc::makeBoxMesh({0, 0, 0}, {1, 1, 1}, {1001, 1000, 1}), std::invalid_argument);
}

TEST(Surface, IsClosedOutwardAndConforming) {
  const dc::Mesh mesh = dc::makeBoxMesh({0, 0, 0}, {1.0, 0.5, 0.25}, {4, 2, 3});
  const std::vector<dc::Triangle> surface = dc::extractSurface(mesh);
  // Each face of the box has 2 cells' worth of triangles per cell: 2 (xy + xz + yz) areas.
  EXPECT_EQ(surface.size(), 2u * 2 * (4 * 2 + 4 * 3 + 2 * 3));
  // Closed: every directed edge appears once, and its reverse once.
  std::map<std::pair<int, int>, int> edges;
  for (const dc::Triangle& t : surface) {
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  }
  for (const auto& [edge, count] : edges) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(edges.count({edge.second, edge.first}), 1u);
  }
  // Outward normals: the divergence theorem gives the volume, sum (c . n) A / 3.
  double volume = 0.0;
  for (const dc::Triangle& t : surface) {
    const Eigen::Vector3d& a = mesh.positions[t[0]];
    const Eigen::Vector3d& b = mesh.positions[t[1]];
    const Eigen::Vector3d& c = mesh.positions[t[2]];
    volume += ((a + b + c) / 3.0).dot((b - a).cross(c - a) / 2.0) / 3.0;
  }
  EXPECT_NEAR(volume, 0.125, 1e-14);
}

TEST(Selection, ByNumbersBoxAndSphere) {
  const dc::Mesh mesh = dc::makeBoxMesh({0, 0, 0}, {1.0, 1.0, 1.0}, {2, 2, 2});
  dc::NodeSelection box;
  box.kind = dc::NodeSelection::Kind::kBox;
  box.box = {{-0.1, -0.1, -0.1}, {0.1, 1.1, 1.1}};
  EXPECT_EQ(dc::selectNodes(mesh, box).size(), 9u);  // the x = 0 face
  dc::NodeSelection sphere;
  sphere.kind = dc::NodeSelection::Kind::kSphere;
  sphere.sphere = {{0.5, 0.5, 0.5}, 0.51};
  EXPECT_EQ(dc::selectNodes(mesh, sphere).size(), 7u);  // centre and its 6 neighbours
  dc::NodeSelection numbers;
  numbers.node_numbers = {27, 1, 1};
  EXPECT_EQ(dc::selectNodes(mesh, numbers), (std::vector<int>{0, 26}));
  numbers.node_numbers = {5, 99};
  try {
    dc::selectNodes(mesh, numbers);
    FAIL() << "expected an unknown node to be refused";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "node 99 is not a node of the mesh");
  }
  sphere.sphere.radius = -1.0;
  EXPECT_THROW(dc::selectNodes(mesh, sphere), std::invalid_argument);
}

TEST(Loads, TractionGivesConsistentNodalForcesWithTheRightResultant) {
  const dc::Mesh mesh = dc::makeBoxMesh({0, 0, 0}, {1.0, 0.1, 0.1}, {5, 2, 2});
  dc::NodeSelection tip;
  tip.kind = dc::NodeSelection::Kind::kBox;
  tip.box = {{0.999, -1, -1}, {1.001, 1, 1}};
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh.numNodes());
  const double area = dc::addTractionLoad(
      mesh, dc::extractBoundary(mesh), dc::selectNodes(mesh, tip), Eigen::Vector3d(0, 0, -2.5), f);
  EXPECT_NEAR(area, 0.01, 1e-15);
  const Eigen::Vector3d resultant = f.reshaped(3, mesh.numNodes()).rowwise().sum();
  EXPECT_NEAR((resultant - Eigen::Vector3d(0, 0, -0.025)).norm(), 0.0, 1e-15);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(3 * mesh.numNodes());
  dc::addTotalForce({0, 1}, Eigen::Vector3d(2, 0, 0), g);
  EXPECT_EQ(g[0], 1.0);
  EXPECT_EQ(g[3], 1.0);
  EXPECT_THROW(dc::addTotalForce({}, Eigen::Vector3d(1, 0, 0), g), std::invalid_argument);
}

TEST(MeshArrays, RoundTripEveryElementTypeAndRefuseWhatDoesNotFit) {
  dc::Mesh mesh = dc::makeBoxMesh({0, 0, 0}, {1.0, 0.5, 0.25}, {2, 1, 1});
  mesh.node_numbers.assign(mesh.positions.size(), 0);
  for (size_t i = 0; i < mesh.node_numbers.size(); ++i) mesh.node_numbers[i] = 100 + 7 * i;
  mesh.cells.push_back({dc::CellType::kHexahedron, {0, 1, 4, 3, 6, 7, 10, 9}});
  mesh.cells.push_back({dc::CellType::kPyramid, {0, 1, 4, 3, 6}});
  const dc::Mesh back = dc::fromArrays(dc::toArrays(mesh), "test");
  EXPECT_EQ(back.positions, mesh.positions);
  EXPECT_EQ(back.node_numbers, mesh.node_numbers);
  EXPECT_EQ(back.tetrahedra, mesh.tetrahedra);
  ASSERT_EQ(back.cells.size(), 2u);
  EXPECT_EQ(back.cells[0].nodes, mesh.cells[0].nodes);
  EXPECT_EQ(back.cells[1].type, dc::CellType::kPyramid);
  const auto refusal = [](dc::MeshArrays arrays) -> std::string {
    try {
      dc::fromArrays(arrays, "the mesh of body 'b'");
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  dc::MeshArrays bad = dc::toArrays(mesh);
  bad.rest_positions.pop_back();
  EXPECT_EQ(refusal(bad), "the mesh of body 'b' has arrays of inconsistent sizes");
  bad = dc::toArrays(mesh);
  bad.tetrahedra[5] = 1000;
  EXPECT_EQ(refusal(bad), "the mesh of body 'b' refers to a node out of range");
  bad = dc::toArrays(mesh);
  bad.cell_types[1] = 7;
  EXPECT_EQ(refusal(bad), "the mesh of body 'b' has a cell of unknown type 7");
  bad = dc::toArrays(mesh);
  bad.cells.pop_back();
  EXPECT_EQ(refusal(bad), "the mesh of body 'b' has arrays of inconsistent sizes");
}

TEST(MeshArrays, RoundTripTheCellFractionsOfAGrid) {
  dc::Mesh mesh =
      dc::makeBoxMesh({0, 0, 0}, {0.2, 0.1, 0.1}, {2, 1, 1}, dc::BoxElement::kHexahedron);
  mesh.cell_fractions = {dc::OctantFractions{1, 1, 1, 1, 1, 1, 1, 1},
                         dc::OctantFractions{0.5, 0, 0.25, 1, 0.125, 0, 0, 0.75}};
  mesh.incompatible_modes = true;
  const dc::Mesh back = dc::fromArrays(dc::toArrays(mesh), "test");
  EXPECT_EQ(back.cell_fractions, mesh.cell_fractions);
  EXPECT_TRUE(back.incompatible_modes);
  dc::MeshArrays bad = dc::toArrays(mesh);
  bad.cell_fractions.pop_back();
  EXPECT_THROW(dc::fromArrays(bad, "test"), std::invalid_argument);
}
