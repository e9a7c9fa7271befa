// Triangle meshes as collision shapes: nearest points on a triangle, the tree against a search of
// every triangle, a closed box mesh and a sphere mesh against their analytic distances, the two
// sides of an open mesh, and what validation rejects.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <memory>
#include <random>

#include "deformable_sim/core/geometry/shape.h"
#include "deformable_sim/core/geometry/triangle_mesh_shape.h"

namespace dc = deformable_sim::core;

namespace {

// A box of `size` centred on the origin, triangles facing out.
dc::TriangleMesh boxMesh(const Eigen::Vector3d& size) {
  return dc::boxSurface(-0.5 * size, 0.5 * size);
}

// An icosahedron subdivided `levels` times and pushed onto the sphere of `radius`.
dc::TriangleMesh sphereMesh(double radius, int levels) {
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  dc::TriangleMesh mesh;
  mesh.vertices = {{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                   {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
  mesh.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                    {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                    {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                    {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> middles;
    auto middle = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto found = middles.find(key);
      if (found != middles.end()) return found->second;
      mesh.vertices.push_back(0.5 * (mesh.vertices[a] + mesh.vertices[b]));
      return middles[key] = static_cast<int>(mesh.vertices.size()) - 1;
    };
    std::vector<Eigen::Vector3i> finer;
    for (const Eigen::Vector3i& t : mesh.triangles) {
      const int ab = middle(t[0], t[1]), bc = middle(t[1], t[2]), ca = middle(t[2], t[0]);
      finer.insert(finer.end(), {{t[0], ab, ca}, {t[1], bc, ab}, {t[2], ca, bc}, {ab, bc, ca}});
    }
    mesh.triangles = finer;
  }
  for (Eigen::Vector3d& v : mesh.vertices) v = radius * v.normalized();
  return mesh;
}

dc::Shape meshShape(dc::TriangleMesh mesh) {
  dc::Shape shape;
  shape.kind = dc::Shape::Kind::kMesh;
  shape.mesh = std::make_shared<const dc::TriangleMeshShape>(std::move(mesh));
  return shape;
}

}  // namespace

TEST(TriangleClosestPoint, FindsTheRightFeature) {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  using Feature = dc::TriangleClosestPoint::Feature;
  auto face = dc::closestPointOnTriangle({0.2, 0.2, 1.0}, a, b, c);
  EXPECT_EQ(face.feature, Feature::kFace);
  EXPECT_TRUE(face.point.isApprox(Eigen::Vector3d(0.2, 0.2, 0.0)));
  auto corner = dc::closestPointOnTriangle({2.0, -1.0, 0.5}, a, b, c);
  EXPECT_EQ(corner.feature, Feature::kVertex);
  EXPECT_EQ(corner.index, 1);
  auto edge = dc::closestPointOnTriangle({1.0, 1.0, 0.0}, a, b, c);  // beyond b-c
  EXPECT_EQ(edge.feature, Feature::kEdge);
  EXPECT_EQ(edge.index, 1);
  EXPECT_TRUE(edge.point.isApprox(Eigen::Vector3d(0.5, 0.5, 0.0)));
  auto other = dc::closestPointOnTriangle({-1.0, 0.5, 0.0}, a, b, c);  // beyond c-a
  EXPECT_EQ(other.feature, Feature::kEdge);
  EXPECT_EQ(other.index, 2);
}

TEST(TriangleAabbTree, FindsWhatASearchOfEveryTriangleFinds) {
  const dc::TriangleMesh mesh = sphereMesh(0.3, 3);  // 1280 triangles
  const dc::TriangleAabbTree tree(mesh);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-0.6, 0.6);
  for (int n = 0; n < 200; ++n) {
    const Eigen::Vector3d p(coordinate(random), coordinate(random), coordinate(random));
    double best = INFINITY;
    for (const Eigen::Vector3i& t : mesh.triangles) {
      const auto closest = dc::closestPointOnTriangle(p, mesh.vertices[t[0]], mesh.vertices[t[1]],
                                                      mesh.vertices[t[2]]);
      best = std::min(best, (p - closest.point).squaredNorm());
    }
    EXPECT_DOUBLE_EQ(tree.nearest(mesh, p).squared_distance, best);
  }
}

TEST(MeshShape, ClosedBoxMatchesTheAnalyticBox) {
  dc::Shape box;
  box.kind = dc::Shape::Kind::kBox;
  box.size = {0.4, 0.6, 1.0};
  const dc::Shape mesh = meshShape(boxMesh(box.size));
  ASSERT_TRUE(mesh.mesh->closed());
  std::mt19937 random(3);
  std::uniform_real_distribution<double> coordinate(-0.8, 0.8);
  for (int n = 0; n < 2000; ++n) {
    const Eigen::Vector3d p(coordinate(random), coordinate(random), coordinate(random));
    Eigen::Vector3d box_surface, box_normal, mesh_surface, mesh_normal;
    const double expected = dc::signedDistance(box, p, &box_surface, &box_normal);
    const double distance = dc::signedDistance(mesh, p, &mesh_surface, &mesh_normal);
    ASSERT_NEAR(distance, expected, 1e-12) << p.transpose();
    EXPECT_LT((mesh_surface - box_surface).norm(), 1e-12) << p.transpose();
    EXPECT_LT((mesh_normal - box_normal).norm(), 1e-9) << p.transpose();
  }
}

// Points on the diagonal edge between a box top's two triangles, brought back from a posed frame
// (inside or outside by rounding only, as a point held on a mesh is found): their normal is the
// top's, not the way of a rounding error. Contact takes a body whose points' normals differ for
// one on several faces.
TEST(MeshShape, APointOnAnEdgeToRoundingHasTheSurfacesNormal) {
  const dc::Shape mesh = meshShape(boxMesh({0.4, 0.6, 0.1}));
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  pose.translation() = Eigen::Vector3d(0.123, -0.456, 0.789);
  const Eigen::Vector3d from(-0.2, -0.3, 0.05), to(0.2, 0.3, 0.05);  // the top's two corners
  int on_edge = 0;
  for (int k = 1; k < 400; ++k) {
    const Eigen::Vector3d p = pose.inverse() * (pose * (from + (to - from) * (k / 400.0)));
    Eigen::Vector3d surface, normal;
    const double distance = dc::signedDistance(mesh, p, &surface, &normal);
    ASSERT_LT(std::abs(distance), 1e-15) << k;
    on_edge += (surface - p).norm() > 0.0;
    EXPECT_NEAR(normal.z(), 1.0, 1e-12) << k << ": " << normal.transpose();
  }
  EXPECT_GT(on_edge, 0);  // some are off the surface by rounding, not all on it exactly
}

TEST(MeshShape, AnInsideOutClosedMeshIsTurnedOutward) {
  dc::TriangleMesh inside_out = boxMesh({1.0, 1.0, 1.0});
  for (Eigen::Vector3i& t : inside_out.triangles) std::swap(t[1], t[2]);
  const dc::Shape mesh = meshShape(inside_out);
  EXPECT_DOUBLE_EQ(dc::signedDistance(mesh, {0.0, 0.0, 0.3}), -0.2);
  EXPECT_DOUBLE_EQ(dc::signedDistance(mesh, {0.0, 0.0, 0.7}), 0.2);
}

TEST(MeshShape, SphereMeshIsWithinItsChordOfTheAnalyticSphere) {
  const double radius = 0.5;
  const dc::Shape mesh = meshShape(sphereMesh(radius, 4));  // 5120 triangles
  // Edges span under 0.07 rad; the flat triangles lie within r (1 - cos 0.07) of the sphere.
  const double chord = radius * (1.0 - std::cos(0.07));
  std::mt19937 random(5);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  for (int n = 0; n < 2000; ++n) {
    const Eigen::Vector3d p(coordinate(random), coordinate(random), coordinate(random));
    Eigen::Vector3d surface, normal;
    const double distance = dc::signedDistance(mesh, p, &surface, &normal);
    ASSERT_NEAR(distance, p.norm() - radius, chord) << p.transpose();
    EXPECT_NEAR(surface.norm(), radius, chord);
    if (std::abs(p.norm() - radius) > 0.05) {
      EXPECT_GT(normal.dot(p.normalized()), 0.99) << p.transpose();
    }
  }
}

TEST(MeshShape, AnOpenMeshIsSolidToItsDepthBehindItsFront) {
  dc::TriangleMesh square;  // 2 m x 2 m in z = 0, facing +z: a table top
  square.vertices = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  square.triangles = {{0, 1, 2}, {0, 2, 3}};
  const auto shape = std::make_shared<const dc::TriangleMeshShape>(square, 0.05);
  EXPECT_FALSE(shape->closed());
  Eigen::Vector3d surface, normal;
  // In front: outside.
  EXPECT_DOUBLE_EQ(shape->signedDistance({0.3, 0.2, 0.1}, &surface, &normal), 0.1);
  EXPECT_EQ(normal, Eigen::Vector3d::UnitZ());
  // Just behind: inside, pushed back out to the front.
  EXPECT_DOUBLE_EQ(shape->signedDistance({0.3, 0.2, -0.01}, &surface, &normal), -0.01);
  EXPECT_EQ(surface, Eigen::Vector3d(0.3, 0.2, 0.0));
  EXPECT_EQ(normal, Eigen::Vector3d::UnitZ());
  // On a diagonal edge shared by the two triangles: the same.
  EXPECT_DOUBLE_EQ(shape->signedDistance({0.2, 0.2, -0.01}, &surface, &normal), -0.01);
  // Farther behind than the depth: free.
  EXPECT_DOUBLE_EQ(shape->signedDistance({0.3, 0.2, -0.08}), 0.08);
  // Behind, but beyond the free edge: free.
  EXPECT_GT(shape->signedDistance({1.01, 0.0, -0.01}), 0.0);
  EXPECT_GT(shape->signedDistance({1.01, 1.01, -0.01}), 0.0);  // past a corner
}

TEST(MeshShape, ValidationSaysWhatIsWrong) {
  auto error = [](dc::TriangleMesh mesh) -> std::string {
    try {
      dc::TriangleMeshShape shape(std::move(mesh));
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "accepted";
  };
  const dc::TriangleMesh box = boxMesh({1.0, 1.0, 1.0});
  EXPECT_EQ(error({box.vertices, {}}), "the mesh has no triangle");
  dc::TriangleMesh bad = box;
  bad.vertices[3].x() = NAN;
  EXPECT_EQ(error(bad), "the mesh has a vertex that is not finite");
  bad = box;
  bad.triangles[4][1] = 8;
  EXPECT_EQ(error(bad), "triangle 4 has a vertex index out of range");
  bad = box;
  bad.vertices.push_back(box.vertices[0] + Eigen::Vector3d(1.0, 0.0, 0.0));
  bad.vertices.push_back(box.vertices[0] + Eigen::Vector3d(2.0, 0.0, 0.0));
  bad.triangles.emplace_back(0, 8, 9);  // its corners on a line
  EXPECT_EQ(error(bad), "triangle 12 has zero area");
  bad = box;
  std::swap(bad.triangles[5][1], bad.triangles[5][2]);
  EXPECT_NE(error(bad).find("not turned consistently"), std::string::npos);
  dc::Shape empty;
  empty.kind = dc::Shape::Kind::kMesh;
  EXPECT_THROW(dc::validate(empty, "obstacles[0]"), std::invalid_argument);
}

TEST(MeshShape, TheRidgesOfABoxAreItsTwelveEdgesNotTheDiagonalsOfItsSides) {
  const dc::TriangleMeshShape box(dc::boxSurface({-1, -1, -1}, {1, 1, 1}));
  int ridges = 0;
  for (int t = 0; t < static_cast<int>(box.mesh().triangles.size()); ++t) {
    for (int k = 0; k < 3; ++k) {
      if (!box.ridge(t, k)) continue;
      ++ridges;
      // Between two sides at right angles, spoken for once.
      const int other = box.across(t, k);
      ASSERT_GE(other, 0);
      EXPECT_NEAR(box.faceNormal(t).dot(box.faceNormal(other)), 0.0, 1e-12);
      for (int j = 0; j < 3; ++j) EXPECT_FALSE(box.across(other, j) == t && box.ridge(other, j));
    }
  }
  EXPECT_EQ(ridges, 12);
  // An open square of two triangles: its four free edges, not its diagonal.
  dc::TriangleMesh square;
  square.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  square.triangles = {{0, 1, 2}, {0, 2, 3}};
  const dc::TriangleMeshShape open(square);
  int free_ridges = 0;
  for (int t = 0; t < 2; ++t) {
    for (int k = 0; k < 3; ++k) free_ridges += open.ridge(t, k) && open.across(t, k) < 0;
  }
  EXPECT_EQ(free_ridges, 4);
  EXPECT_FALSE(open.ridge(0, 2) || open.ridge(1, 0));  // the diagonal 0-2, both ways
}
