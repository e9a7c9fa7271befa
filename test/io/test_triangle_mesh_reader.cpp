// Tests for the surface mesh loader: the same unit cube written as ascii STL, binary STL, OBJ and
// a DAE in centimetres reads back as 8 vertices and 12 outward triangles; scale, URIs and errors.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "deformable_sim/io/triangle_mesh_reader.h"
#include "thrown_message.h"

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
  return test::thrownMessage<TriangleMeshError>([&] { readTriangleMesh(path); },
                                                path + " was read");
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

// A tetrahedron's four triangles as an ascii STL, with corner `corner` of triangle `triangle`
// (from 1) written as `bad`.
std::string tetrahedronStl(int triangle, int corner, const std::string& bad) {
  const char* corners[4][3] = {{"0 0 0", "0 1 0", "1 0 0"},
                               {"0 0 0", "1 0 0", "0 0 1"},
                               {"0 0 0", "0 0 1", "0 1 0"},
                               {"1 0 0", "0 1 0", "0 0 1"}};
  std::string text = "solid t\n";
  for (int t = 0; t < 4; ++t) {
    text += "facet normal 0 0 0\nouter loop\n";
    for (int c = 0; c < 3; ++c) {
      text += std::string("vertex ") +
              (t + 1 == triangle && c + 1 == corner ? bad : std::string(corners[t][c])) + "\n";
    }
    text += "endloop\nendfacet\n";
  }
  return text + "endsolid t\n";
}

// The same four triangles as a binary STL, with one coordinate replaced by `bad`.
std::string tetrahedronBinaryStl(int triangle, int corner, float bad) {
  const float corners[4][3][3] = {{{0, 0, 0}, {0, 1, 0}, {1, 0, 0}},
                                  {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}},
                                  {{0, 0, 0}, {0, 0, 1}, {0, 1, 0}},
                                  {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  std::string bytes(80, ' ');
  const uint32_t count = 4;
  bytes.append(reinterpret_cast<const char*>(&count), 4);
  for (int t = 0; t < 4; ++t) {
    float record[12] = {0, 0, 0};
    for (int c = 0; c < 3; ++c) std::memcpy(record + 3 + 3 * c, corners[t][c], sizeof(float) * 3);
    if (t + 1 == triangle) record[3 + 3 * (corner - 1)] = bad;
    bytes.append(reinterpret_cast<const char*>(record), sizeof record);
    bytes.append(2, '\0');
  }
  return bytes;
}

std::string writeTemporary(const std::string& name, const std::string& bytes) {
  const std::string path =
      (std::filesystem::temp_directory_path() / (std::to_string(getpid()) + "_" + name)).string();
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

TEST(TriangleMeshReader, ReadsFromMemoryAsFromAFile) {
  for (const char* name : {"cube_ascii.stl", "cube_binary.stl", "cube.obj"}) {
    std::ifstream file(kMeshes + name, std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
    const std::string format = std::filesystem::path(name).extension().string().substr(1);
    expectUnitCube(readTriangleMeshFromMemory(bytes, format, name), 1.0);
  }
  EXPECT_EQ(
      readTriangleMeshFromMemory(tetrahedronBinaryStl(0, 0, 0.0f), "stl", "t.stl").triangles.size(),
      4u);
  EXPECT_EQ(readTriangleMeshFromMemory("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "obj", "t.obj")
                .triangles.size(),
            1u);
  EXPECT_THROW(readTriangleMeshFromMemory("", "stl", "t.stl"), TriangleMeshError);
  EXPECT_THROW(readTriangleMeshFromMemory("v 0 0 0\n", "xyz", "t.xyz"), TriangleMeshError);
}

TEST(TriangleMeshReader, TrianglesWhoseCornersCoincideAreDroppedAndCounted) {
  // Triangle 2's third corner on its first: the reader merges them, and the triangle goes.
  int collapsed = -1;
  const core::TriangleMesh mesh = readTriangleMeshFromMemory(
      tetrahedronStl(2, 3, "0 0 0"), "stl", "t.stl", Eigen::Vector3d::Ones(), &collapsed);
  EXPECT_EQ(mesh.triangles.size(), 3u);
  EXPECT_EQ(collapsed, 1);
}

// The message of the error reading `bytes` as a file `name`, from disk and from memory (the
// same).
std::string nonFiniteError(const std::string& name, const std::string& bytes) {
  const std::string path = writeTemporary(name, bytes);
  const std::string from_file = errorOf(path);
  std::filesystem::remove(path);
  std::string from_memory = "(read)";
  try {
    readTriangleMeshFromMemory(bytes, std::filesystem::path(name).extension().string().substr(1),
                               path);
  } catch (const TriangleMeshError& e) {
    from_memory = e.what();
  }
  EXPECT_EQ(from_file, from_memory);
  EXPECT_NE(from_file.find(path), std::string::npos) << from_file;
  return from_file.substr(from_file.find(path) + path.size());
}

TEST(TriangleMeshReader, ANonFiniteCoordinateIsAnErrorNamingTheFileTriangleAndCorner) {
  EXPECT_EQ(nonFiniteError("nan.stl", tetrahedronStl(3, 2, "nan 0 1")),
            "': corner 2 of triangle 3 has a non-finite coordinate (nan 0 1)");
  EXPECT_EQ(nonFiniteError("inf.stl", tetrahedronStl(4, 1, "0 inf 0")),
            "': corner 1 of triangle 4 has a non-finite coordinate (0 inf 0)");
  EXPECT_EQ(nonFiniteError("nan_binary.stl",
                           tetrahedronBinaryStl(2, 3, std::numeric_limits<float>::quiet_NaN())),
            "': corner 3 of triangle 2 has a non-finite coordinate (nan 0 1)");
  EXPECT_EQ(nonFiniteError("inf.obj", "v 0 0 0\nv 1 0 0\nv 0 1 -inf\nf 1 2 3\n"),
            "': corner 3 of triangle 1 has a non-finite coordinate (0 1 -inf)");
  // A finite coordinate that the scale makes infinite, too.
  const std::string path = writeTemporary("big.stl", tetrahedronStl(1, 1, "1e38 0 0"));
  try {
    readTriangleMesh(path, Eigen::Vector3d::Constant(1e300));
    ADD_FAILURE() << "no error";
  } catch (const TriangleMeshError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("non-finite coordinate (1e+38 0 0) once scaled by (1e+300 1e+300 "
                           "1e+300)"),
              std::string::npos)
        << message;
  }
  std::filesystem::remove(path);
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
