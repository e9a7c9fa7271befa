// Nodal forces from loads: a uniform traction's consistent loads carry its resultant and its
// moment (the face's area times its centroid), on triangles and on quadrilaterals that are not
// parallelograms; only faces wholly selected are loaded; a total force is shared equally.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/elements/loads.h"
#include "deformable_sim/core/elements/mesh.h"
#include "thrown_message.h"

namespace dc = deformable_sim::core;
namespace dt = deformable_sim::test;

namespace {

Eigen::Vector3d resultant(const Eigen::VectorXd& f) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int i = 0; i < f.size() / 3; ++i) sum += f.segment<3>(3 * i);
  return sum;
}

// The moment of the nodal forces about the origin.
Eigen::Vector3d moment(const dc::Mesh& mesh, const Eigen::VectorXd& f) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int i = 0; i < mesh.numNodes(); ++i) sum += mesh.positions[i].cross(f.segment<3>(3 * i));
  return sum;
}

// The nodes with coordinate `axis` equal to `value`.
std::vector<int> nodesAt(const dc::Mesh& mesh, int axis, double value) {
  std::vector<int> nodes;
  for (int i = 0; i < mesh.numNodes(); ++i) {
    if (mesh.positions[i][axis] == value) nodes.push_back(i);
  }
  return nodes;
}

// One hexahedron over [0, 1]^3 whose top is narrowed to y <= 0.5: its face at x = 1 is the
// trapezoid with parallel sides 1 (z = 0) and 0.5 (z = 1), height 1.
dc::Mesh narrowedHexahedron() {
  dc::Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0},   {0, 1, 0},
                    {0, 0, 1}, {1, 0, 1}, {1, 0.5, 1}, {0, 0.5, 1}};
  mesh.node_numbers = {1, 2, 3, 4, 5, 6, 7, 8};
  mesh.cells.push_back({dc::CellType::kHexahedron, {0, 1, 2, 3, 4, 5, 6, 7}});
  return mesh;
}

}  // namespace

TEST(Loads, TractionOnTrianglesCarriesItsResultantAndMoment) {
  // The end x = 0.75 of a tetrahedral bar: area 0.5 x 0.25, centroid (0.75, 0.25, 0.125).
  const dc::Mesh mesh = dc::makeBoxMesh({0, 0, 0}, {0.75, 0.5, 0.25}, {3, 2, 2});
  const Eigen::Vector3d traction(100.0, -20.0, 35.0);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh.numNodes());
  const double area =
      dc::addTractionLoad(mesh, dc::extractBoundary(mesh), nodesAt(mesh, 0, 0.75), traction, f);
  EXPECT_NEAR(area, 0.125, 1e-16);
  EXPECT_NEAR((resultant(f) - area * traction).norm(), 0.0, 1e-13);
  EXPECT_NEAR((moment(mesh, f) - Eigen::Vector3d(0.75, 0.25, 0.125).cross(area * traction)).norm(),
              0.0, 1e-13);
  // No force on any node off the loaded face.
  for (int i = 0; i < mesh.numNodes(); ++i) {
    if (mesh.positions[i].x() != 0.75) {
      EXPECT_EQ(Eigen::Vector3d(f.segment<3>(3 * i)), Eigen::Vector3d::Zero()) << i;
    }
  }
}

TEST(Loads, TractionOnAParallelogramGivesAQuarterToEachCorner) {
  const dc::Mesh mesh =
      dc::makeBoxMesh({0, 0, 0}, {0.3, 0.2, 0.1}, {1, 1, 1}, dc::BoxElement::kHexahedron);
  const Eigen::Vector3d traction(0.0, 0.0, -50.0);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh.numNodes());
  const double area =
      dc::addTractionLoad(mesh, dc::extractBoundary(mesh), nodesAt(mesh, 2, 0.1), traction, f);
  EXPECT_NEAR(area, 0.06, 1e-16);
  for (int i : nodesAt(mesh, 2, 0.1)) {
    EXPECT_NEAR((f.segment<3>(3 * i) - 0.25 * area * traction).norm(), 0.0, 1e-14) << i;
  }
}

TEST(Loads, TractionOnATrapezoidIsExactInItsAreaAndCentroid) {
  // Area (1 + 0.5) / 2; centroid y = integral of y over the area / area = (7/24) / (3/4),
  // z = h (a + 2b) / (3 (a + b)) = 4/9.
  const dc::Mesh mesh = narrowedHexahedron();
  ASSERT_GT(dc::totalVolume(mesh), 0.0);
  const Eigen::Vector3d traction(-3.0, 1.0, 2.0);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(24);
  const double area =
      dc::addTractionLoad(mesh, dc::extractBoundary(mesh), {1, 2, 5, 6}, traction, f);
  EXPECT_NEAR(area, 0.75, 1e-15);
  EXPECT_NEAR((resultant(f) - 0.75 * traction).norm(), 0.0, 1e-14);
  const Eigen::Vector3d centroid(1.0, 7.0 / 18.0, 4.0 / 9.0);
  EXPECT_NEAR((moment(mesh, f) - centroid.cross(0.75 * traction)).norm(), 0.0, 1e-14);
  // The wider edge takes more than the narrower: not a plain quarter each.
  EXPECT_GT(f.segment<3>(3 * 2).norm(), f.segment<3>(3 * 6).norm());
}

TEST(Loads, OnlyFacesWithEveryNodeSelectedAreLoaded) {
  const dc::Mesh mesh = narrowedHexahedron();
  const std::vector<dc::Face> boundary = dc::extractBoundary(mesh);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(24);
  // Three of the face's four corners: nothing.
  EXPECT_EQ(dc::addTractionLoad(mesh, boundary, {1, 2, 5}, {1, 0, 0}, f), 0.0);
  EXPECT_TRUE(f.isZero(0.0));
  // Every node: the whole surface. Its faces: z = 0 (1), z = 1 (0.5), y = 0 (1), x = 0 and
  // x = 1 (0.75 each) and the slope from y = 1 down to y = 0.5 (sqrt(1.25)).
  const double area = dc::addTractionLoad(mesh, boundary, {0, 1, 2, 3, 4, 5, 6, 7}, {0, 0, 7.0}, f);
  EXPECT_NEAR(area, 4.0 + std::sqrt(1.25), 1e-14);
  EXPECT_NEAR((resultant(f) - area * Eigen::Vector3d(0, 0, 7.0)).norm(), 0.0, 1e-13);
  // Adding loads accumulates in f.
  Eigen::VectorXd twice = 2.0 * f;
  dc::addTractionLoad(mesh, boundary, {0, 1, 2, 3, 4, 5, 6, 7}, {0, 0, 7.0}, f);
  EXPECT_NEAR((f - twice).norm(), 0.0, 1e-14);
}

TEST(Loads, ATotalForceIsSharedEquallyAndNeedsANode) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(15);
  f.segment<3>(3) = Eigen::Vector3d(1.0, 1.0, 1.0);  // an earlier load stays
  dc::addTotalForce({1, 3, 4}, Eigen::Vector3d(3.0, -6.0, 0.3), f);
  EXPECT_EQ(Eigen::Vector3d(f.segment<3>(0)), Eigen::Vector3d::Zero());
  EXPECT_NEAR((f.segment<3>(3) - Eigen::Vector3d(2.0, -1.0, 1.1)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((f.segment<3>(9) - Eigen::Vector3d(1.0, -2.0, 0.1)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((f.segment<3>(12) - Eigen::Vector3d(1.0, -2.0, 0.1)).norm(), 0.0, 1e-15);
  EXPECT_EQ(dt::thrownMessage<std::invalid_argument>(
                [&] { dc::addTotalForce({}, Eigen::Vector3d(1, 0, 0), f); }, "accepted"),
            "total_force: no node selected");
}
