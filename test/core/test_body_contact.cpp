// Contact between bodies and of a body with itself: the broad phase
// (bounding-volume tree over a body's surface triangles), the swept
// node-triangle test, and scenes through the core.
#include <gtest/gtest.h>

#include <random>

#include "deformable_sim/core/aabb_tree.h"
#include "deformable_sim/core/body_surface.h"
#include "deformable_sim/core/box_mesh.h"
#include "deformable_sim/core/node_triangle.h"

namespace dc = deformable_sim::core;

namespace {

std::vector<dc::Box3> randomBoxes(std::mt19937 &random, int count) {
  std::uniform_real_distribution<double> where(-1.0, 1.0), size(0.0, 0.2);
  std::vector<dc::Box3> boxes;
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector3d min(where(random), where(random), where(random));
    boxes.emplace_back(
        min, min + Eigen::Vector3d(size(random), size(random), size(random)));
  }
  return boxes;
}

std::vector<int> overlapping(const dc::AabbTree &tree, const dc::Box3 &box) {
  std::vector<int> found;
  tree.query(box, [&](int item) { found.push_back(item); });
  std::sort(found.begin(), found.end());
  return found;
}

std::vector<int> overlappingByHand(const std::vector<dc::Box3> &boxes,
                                   const dc::Box3 &box) {
  std::vector<int> found;
  for (size_t k = 0; k < boxes.size(); ++k) {
    if (boxes[k].intersects(box))
      found.push_back(static_cast<int>(k));
  }
  return found;
}

} // namespace

TEST(AabbTree, FindsExactlyTheOverlappingBoxesBeforeAndAfterARefit) {
  std::mt19937 random(7);
  std::vector<dc::Box3> boxes = randomBoxes(random, 500);
  dc::AabbTree tree;
  tree.build(boxes);
  const std::vector<dc::Box3> queries = randomBoxes(random, 50);
  for (const dc::Box3 &q : queries)
    EXPECT_EQ(overlapping(tree, q), overlappingByHand(boxes, q));
  // Every box moves elsewhere: the same tree, refitted, still answers exactly.
  boxes = randomBoxes(random, 500);
  tree.refit(boxes);
  int hits = 0;
  for (const dc::Box3 &q : queries) {
    EXPECT_EQ(overlapping(tree, q), overlappingByHand(boxes, q));
    hits += static_cast<int>(overlapping(tree, q).size());
  }
  EXPECT_GT(hits, 0);
  EXPECT_LT(tree.numNodes(), 2 * 500 / dc::AabbTree::kLeafSize * 2);
}

TEST(BodySurface, AreTheBoundaryTrianglesAndNodesOfAnyMesh) {
  for (dc::BoxElement element :
       {dc::BoxElement::kTetrahedron, dc::BoxElement::kHexahedron}) {
    const dc::Mesh mesh =
        dc::makeBoxMesh({0, 0, 0}, {0.2, 0.2, 0.1}, {2, 2, 1}, element);
    Eigen::VectorXd x(3 * mesh.numNodes());
    for (int i = 0; i < mesh.numNodes(); ++i)
      x.segment<3>(3 * i) = mesh.positions[i];
    const dc::BodySurface surface(mesh, x, true);
    EXPECT_EQ(surface.triangles().size(),
              2u * (2 * 4 + 4 * 2));        // 8 quads top/bottom, 8 sides
    EXPECT_EQ(surface.nodes().size(), 18u); // all nodes are on it
    EXPECT_NEAR(surface.size(), std::sqrt(0.09), 1e-12);
    EXPECT_NEAR(surface.shortestEdge(), 0.1, 1e-12);
    EXPECT_TRUE(surface.adjacent(0, 1));
    EXPECT_FALSE(surface.adjacent(0, 2)); // two cells apart along x
    // Swept upwards by 1 m: the tree's root covers start and end.
    Eigen::VectorXd up = x;
    for (int i = 0; i < mesh.numNodes(); ++i)
      up[3 * i + 2] += 1.0;
    dc::BodySurface moving(mesh, x, false);
    moving.sweep(up, 0.01);
    EXPECT_NEAR(moving.tree().rootBox().min().z(), -0.01, 1e-12);
    EXPECT_NEAR(moving.tree().rootBox().max().z(), 1.11, 1e-12);
  }
}

TEST(NodeTriangle,
     ANodeThatCameThroughIsFoundDeepANodeInsideFromTheStartOnlyWhenShallow) {
  dc::SweptTriangle floor; // z = 0, outward normal +z, still
  floor.start[0] = floor.end[0] = {0, 0, 0};
  floor.start[1] = floor.end[1] = {1, 0, 0};
  floor.start[2] = floor.end[2] = {0, 1, 0};
  dc::NodeTriangleHit hit;
  // Through the triangle within the step, ending 0.5 m below it: found, by the
  // side it came from.
  EXPECT_TRUE(dc::nodeHitsTriangle({{0.2, 0.2, 0.3}, {0.2, 0.2, -0.5}}, floor,
                                   1e-3, 0.01, &hit));
  EXPECT_DOUBLE_EQ(hit.depth, 0.5);
  EXPECT_EQ(hit.normal, Eigen::Vector3d::UnitZ());
  EXPECT_NEAR(hit.weights.sum(), 1.0, 1e-15);
  EXPECT_TRUE(hit.weights.isApprox(Eigen::Vector3d(0.6, 0.2, 0.2)));
  // Deep below from the start (the far side of a body): not this triangle's
  // business.
  EXPECT_FALSE(dc::nodeHitsTriangle({{0.2, 0.2, -0.4}, {0.2, 0.2, -0.5}}, floor,
                                    1e-3, 0.01, &hit));
  // Shallow below from the start (resting on it): found.
  EXPECT_TRUE(dc::nodeHitsTriangle({{0.2, 0.2, -0.004}, {0.2, 0.2, -0.005}},
                                   floor, 1e-3, 0.01, &hit));
  // In front, or beside the triangle: not.
  EXPECT_FALSE(dc::nodeHitsTriangle({{0.2, 0.2, 0.3}, {0.2, 0.2, 0.1}}, floor,
                                    1e-3, 0.01, &hit));
  EXPECT_FALSE(dc::nodeHitsTriangle({{0.8, 0.8, 0.3}, {0.8, 0.8, -0.1}}, floor,
                                    1e-3, 0.01, &hit));
  // A triangle that rises through a still node catches it too.
  dc::SweptTriangle rising = floor;
  for (Eigen::Vector3d &corner : rising.end)
    corner.z() = 0.5;
  EXPECT_TRUE(dc::nodeHitsTriangle({{0.2, 0.2, 0.1}, {0.2, 0.2, 0.1}}, rising,
                                   1e-3, 0.01, &hit));
  EXPECT_NEAR(hit.depth, 0.4, 1e-15);
}
