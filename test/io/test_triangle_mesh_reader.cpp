// Tests for the surface mesh loader: the same unit cube written as ascii STL, binary STL, OBJ and
// a DAE in centimetres reads back as 8 vertices and 12 outward triangles; scale, URIs and errors.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <string>

#include "deformable_sim/io/triangle_mesh_reader.h"

namespace deformable_sim::io {
namespace {

const std::string kMeshes = DEFORMABLE_SIM_SOURCE_DIR "/test/data/meshes/";

// Six times the enclosed volume's contribution of each triangle, summed: > 0 when they face out.
double enclosedVolume(const core::TriangleMesh& mesh) {
  double six_volume = 0.0;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    six_volume += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
  }
  return six_volume / 6.0;
}

void expectUnitCube(const core::TriangleMesh& mesh, double edge) {
  EXPECT_EQ(mesh.vertices.size(), 8u);  // an STL's repeated corners merged
  EXPECT_EQ(mesh.triangles.size(), 12u);
  EXPECT_NEAR(enclosedVolume(mesh), edge * edge * edge, 1e-9);
  for (const Eigen::Vector3d& v : mesh.vertices) {
    EXPECT_NEAR(v.cwiseAbs().maxCoeff(), 0.5 * edge, 1e-9);
  }
}

TEST(TriangleMeshReader, ReadsTheCubeInEveryFormat) {
  expectUnitCube(readTriangleMesh(kMeshes + "cube_ascii.stl"), 1.0);
  expectUnitCube(readTriangleMesh(kMeshes + "cube_binary.stl"), 1.0);
  expectUnitCube(readTriangleMesh(kMeshes + "cube.obj"), 1.0);  // quads split into triangles
}

TEST(TriangleMeshReader, AppliesTheUnitOfADaeFile) {
  expectUnitCube(readTriangleMesh(kMeshes + "cube_cm.dae"), 1.0);  // 100 cm
}

TEST(TriangleMeshReader, ScalesPerAxis) {
  const core::TriangleMesh mesh =
      readTriangleMesh(kMeshes + "cube_binary.stl", Eigen::Vector3d(2.0, 3.0, 0.5));
  EXPECT_NEAR(enclosedVolume(mesh), 3.0, 1e-9);
  EXPECT_NEAR(mesh.vertices[0].cwiseAbs().x(), 1.0, 1e-9);
  EXPECT_NEAR(mesh.vertices[0].cwiseAbs().y(), 1.5, 1e-9);
}

TEST(TriangleMeshReader, AMirroringScaleKeepsTheTrianglesFacingOut) {
  const core::TriangleMesh mesh =
      readTriangleMesh(kMeshes + "cube.obj", Eigen::Vector3d(-1.0, 1.0, 1.0));
  EXPECT_NEAR(enclosedVolume(mesh), 1.0, 1e-9);
}

TEST(TriangleMeshReader, ReadsAnOpenMesh) {
  const core::TriangleMesh mesh = readTriangleMesh(kMeshes + "square_open.obj");
  EXPECT_EQ(mesh.vertices.size(), 4u);
  EXPECT_EQ(mesh.triangles.size(), 2u);
}

std::string errorOf(const std::string& path) {
  try {
    readTriangleMesh(path);
  } catch (const TriangleMeshError& e) {
    return e.what();
  }
  ADD_FAILURE() << path << " was read";
  return "";
}

TEST(TriangleMeshReader, ErrorsNameTheFile) {
  const std::string missing = errorOf(kMeshes + "nowhere.stl");
  EXPECT_NE(missing.find("nowhere.stl"), std::string::npos) << missing;
  EXPECT_NE(missing.find("no such file"), std::string::npos) << missing;
  const std::string unknown = errorOf(kMeshes + "two_tets_0based.node");
  EXPECT_NE(unknown.find("two_tets_0based.node"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("unknown format"), std::string::npos) << unknown;
  const std::string empty = errorOf(kMeshes + "no_triangles.obj");
  EXPECT_NE(empty.find("no_triangles.obj"), std::string::npos) << empty;
  EXPECT_NE(empty.find("no triangle"), std::string::npos) << empty;
}

TEST(TriangleMeshReader, ResolvesUris) {
  EXPECT_EQ(resolveMeshUri("meshes/a.stl"), "meshes/a.stl");
  EXPECT_EQ(resolveMeshUri("file:///tmp/a.stl"), "/tmp/a.stl");
  const PackageResolver resolver = [](const std::string& uri) {
    return uri == "package://robot/meshes/a.stl" ? std::string("/robot/meshes/a.stl") : "";
  };
  EXPECT_EQ(resolveMeshUri("package://robot/meshes/a.stl", resolver), "/robot/meshes/a.stl");
  EXPECT_THROW(resolveMeshUri("package://other/a.stl", resolver), TriangleMeshError);
  EXPECT_THROW(resolveMeshUri("package://robot/meshes/a.stl"), TriangleMeshError);
  EXPECT_THROW(resolveMeshUri("http://example.org/a.stl"), TriangleMeshError);
}

}  // namespace
}  // namespace deformable_sim::io
