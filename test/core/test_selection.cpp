// Selecting nodes: by file numbers (ascending, without repeats), by a closed box or ball at rest
// or where the nodes are now, and the messages for what cannot select anything sensible.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/elements/mesh.h"
#include "deformable_sim/core/elements/selection.h"
#include "element_test_helpers.h"
#include "thrown_message.h"

namespace dc = deformable_sim::core;
namespace dt = deformable_sim::test;

namespace {

// A 2 x 2 x 2 grid of unit cubes over [0, 2]^3: nodes at integer points, index x + 3 y + 9 z.
dc::Mesh unitGrid() { return dc::makeBoxMesh({0, 0, 0}, {2, 2, 2}, {2, 2, 2}); }

dc::NodeSelection boxSelection(const Eigen::Vector3d& min, const Eigen::Vector3d& max) {
  dc::NodeSelection selection;
  selection.kind = dc::NodeSelection::Kind::kBox;
  selection.box = {min, max};
  return selection;
}

dc::NodeSelection ballSelection(const Eigen::Vector3d& centre, double radius) {
  dc::NodeSelection selection;
  selection.kind = dc::NodeSelection::Kind::kSphere;
  selection.sphere = {centre, radius};
  return selection;
}

std::string refusal(const dc::Mesh& mesh, const dc::NodeSelection& selection) {
  return dt::thrownMessage<std::invalid_argument>([&] { dc::selectNodes(mesh, selection); },
                                                  "accepted");
}

}  // namespace

TEST(Selection, ByNumbersInAscendingIndexOrderWithoutRepeats) {
  dc::Mesh mesh = unitGrid();
  // Numbers that are not the indices plus one: the file's own, in another order.
  for (int i = 0; i < mesh.numNodes(); ++i) mesh.node_numbers[i] = 1000 - 10 * i;
  dc::NodeSelection numbers;
  numbers.node_numbers = {1000, 740, 990, 740, 1000};
  EXPECT_EQ(dc::selectNodes(mesh, numbers), (std::vector<int>{0, 1, 26}));
  numbers.node_numbers = {};
  EXPECT_TRUE(dc::selectNodes(mesh, numbers).empty());
  numbers.node_numbers = {990, 5};
  EXPECT_EQ(refusal(mesh, numbers), "node 5 is not a node of the mesh");
}

TEST(Selection, ABoxIsClosedOnEverySide) {
  const dc::Mesh mesh = unitGrid();
  // Exactly the faces of the box [1, 2] x [0, 1] x [1, 1]: the nodes on its edges count.
  EXPECT_EQ(dc::selectNodes(mesh, boxSelection({1, 0, 1}, {2, 1, 1})),
            (std::vector<int>{10, 11, 13, 14}));
  // A box of no volume at a node selects that node alone.
  EXPECT_EQ(dc::selectNodes(mesh, boxSelection({1, 1, 1}, {1, 1, 1})), std::vector<int>{13});
  // Between the grid's planes: nothing, and that is not an error here.
  EXPECT_TRUE(dc::selectNodes(mesh, boxSelection({0.1, 0.1, 0.1}, {0.9, 0.9, 0.9})).empty());
  // Around everything.
  EXPECT_EQ(dc::selectNodes(mesh, boxSelection({-1, -1, -1}, {3, 3, 3})).size(), 27u);
}

TEST(Selection, ABallIsClosedToo) {
  const dc::Mesh mesh = unitGrid();
  // Radius 1 about the centre node: it and its six neighbours, at exactly 1.
  EXPECT_EQ(dc::selectNodes(mesh, ballSelection({1, 1, 1}, 1.0)),
            (std::vector<int>{4, 10, 12, 13, 14, 16, 22}));
  // Radius sqrt(2): the twelve at distance sqrt(2) join them; the corners (sqrt 3) do not.
  EXPECT_EQ(dc::selectNodes(mesh, ballSelection({1, 1, 1}, std::sqrt(2.0) + 1e-12)).size(),
            7u + 12u);
  // Radius 0 at a node: that node.
  EXPECT_EQ(dc::selectNodes(mesh, ballSelection({2, 0, 2}, 0.0)), std::vector<int>{20});
}

TEST(Selection, AtPositionsSelectsWhereTheNodesAreNow) {
  const dc::Mesh mesh = unitGrid();
  // The body moved by +5 in x: the box about the rest position selects nothing now, the moved
  // one what the rest one selected at rest.
  Eigen::VectorXd moved = dt::stacked(mesh);
  for (int i = 0; i < mesh.numNodes(); ++i) moved[3 * i] += 5.0;
  const dc::NodeSelection at_rest = boxSelection({-0.5, -0.5, -0.5}, {0.5, 2.5, 2.5});
  const dc::NodeSelection shifted = boxSelection({4.5, -0.5, -0.5}, {5.5, 2.5, 2.5});
  EXPECT_TRUE(dc::selectNodesAt(mesh, moved, at_rest).empty());
  EXPECT_EQ(dc::selectNodesAt(mesh, moved, shifted), dc::selectNodes(mesh, at_rest));
  EXPECT_EQ(dc::selectNodes(mesh, at_rest).size(), 9u);
  // At the rest positions the two functions agree for every kind.
  const Eigen::VectorXd rest = dt::stacked(mesh);
  const dc::NodeSelection ball = ballSelection({0, 0, 0}, 1.5);
  EXPECT_EQ(dc::selectNodesAt(mesh, rest, ball), dc::selectNodes(mesh, ball));
  // Numbers do not depend on where the nodes are.
  dc::NodeSelection numbers;
  numbers.node_numbers = {27, 3};
  EXPECT_EQ(dc::selectNodesAt(mesh, moved, numbers), (std::vector<int>{2, 26}));
}

TEST(Selection, RegionsThatCannotBeAreRefused) {
  const dc::Mesh mesh = unitGrid();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::string bad_box = "box: min must not exceed max on any axis (and be finite)";
  EXPECT_EQ(refusal(mesh, boxSelection({0, 0, 1.1}, {2, 2, 1})), bad_box);
  EXPECT_EQ(refusal(mesh, boxSelection({0, nan, 0}, {2, 2, 2})), bad_box);
  EXPECT_EQ(refusal(mesh, boxSelection({0, 0, 0}, {inf, 2, 2})), bad_box);
  const std::string bad_ball = "sphere: radius must be finite and >= 0, centre finite";
  EXPECT_EQ(refusal(mesh, ballSelection({1, 1, 1}, -1e-9)), bad_ball);
  EXPECT_EQ(refusal(mesh, ballSelection({1, 1, 1}, nan)), bad_ball);
  EXPECT_EQ(refusal(mesh, ballSelection({1, 1, 1}, inf)), bad_ball);
  EXPECT_EQ(refusal(mesh, ballSelection({1, nan, 1}, 1.0)), bad_ball);
  // selectNodesAt checks the same.
  EXPECT_THROW(dc::selectNodesAt(mesh, dt::stacked(mesh), ballSelection({1, 1, 1}, -1.0)),
               std::invalid_argument);
}
