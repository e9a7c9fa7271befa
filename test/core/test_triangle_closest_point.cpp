// The nearest point of a triangle and the feature it lies on, which decides the sign of a mesh's
// distance.
#include <gtest/gtest.h>

#include "deformable_sim/core/geometry/triangle_closest_point.h"

namespace dc = deformable_sim::core;
using Feature = dc::TriangleClosestPoint::Feature;

namespace {

const Eigen::Vector3d kA(0, 0, 0), kB(1, 0, 0), kC(0, 1, 0);

dc::TriangleClosestPoint nearest(const Eigen::Vector3d& p) {
  return dc::closestPointOnTriangle(p, kA, kB, kC);
}

}  // namespace

TEST(TriangleClosestPoint, AboveTheInsideIsTheFootOnTheFace) {
  for (double height : {1.0, -0.5, 0.0}) {
    const dc::TriangleClosestPoint q = nearest({0.2, 0.3, height});
    EXPECT_EQ(q.feature, Feature::kFace) << height;
    EXPECT_LT((q.point - Eigen::Vector3d(0.2, 0.3, 0.0)).norm(), 1e-12) << height;
  }
}

TEST(TriangleClosestPoint, BeyondACornerIsThatCorner) {
  const Eigen::Vector3d corners[3] = {kA, kB, kC};
  const Eigen::Vector3d beyond[3] = {{-1, -1, 0.5}, {2, -0.5, 0}, {-0.5, 2, -1}};
  for (int k = 0; k < 3; ++k) {
    const dc::TriangleClosestPoint q = nearest(beyond[k]);
    EXPECT_EQ(q.feature, Feature::kVertex) << k;
    EXPECT_EQ(q.index, k);
    EXPECT_LT((q.point - corners[k]).norm(), 1e-12) << k;
  }
}

TEST(TriangleClosestPoint, BesideAnEdgeIsItsFootOnThatEdgeNumberedFromItsFirstCorner) {
  struct Case {
    Eigen::Vector3d p, foot;
    int edge;
  };
  const Case cases[] = {{{0.5, -1, 0.3}, {0.5, 0, 0}, 0},    // a to b
                        {{1, 1, 0}, {0.5, 0.5, 0}, 1},       // b to c
                        {{-2, 0.25, -1}, {0, 0.25, 0}, 2}};  // c to a
  for (const Case& c : cases) {
    const dc::TriangleClosestPoint q = nearest(c.p);
    EXPECT_EQ(q.feature, Feature::kEdge) << c.edge;
    EXPECT_EQ(q.index, c.edge);
    EXPECT_LT((q.point - c.foot).norm(), 1e-12) << c.edge;
  }
}
