// Tests for the Gmsh and TetGen mesh readers: the shipped reference meshes in all three formats,
// small hand-written meshes that need repairs, and malformed files whose errors must point at
// the file, the line and the node or element.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>
#include <vector>

#include "deformable_sim/core/elements/mesh.h"
#include "deformable_sim/io/mesh_reader.h"
#include "thrown_message.h"

namespace deformable_sim::io {
namespace {

namespace fs = std::filesystem;

const std::string kReferenceMeshes = DEFORMABLE_SIM_REFERENCE_DIR "/meshes/";
const std::string kTestMeshes = DEFORMABLE_SIM_SOURCE_DIR "/test/data/meshes/";

// Passes when `text` contains every one of `parts`; on failure shows the whole text.
::testing::AssertionResult containsAll(const std::string& text,
                                       std::initializer_list<std::string> parts) {
  for (const std::string& part : parts) {
    if (text.find(part) == std::string::npos) {
      return ::testing::AssertionFailure()
             << "\"" << text << "\"\n  does not contain \"" << part << "\"";
    }
  }
  return ::testing::AssertionSuccess();
}

// The MeshError message of `read`, or a test failure if it does not throw one.
template <typename Read>
std::string errorOf(Read read) {
  return test::thrownMessage<MeshError>(read, "expected a MeshError");
}

void expectSameMesh(const core::Mesh& a, const core::Mesh& b) {
  EXPECT_EQ(a.node_numbers, b.node_numbers);
  EXPECT_EQ(a.tetrahedra, b.tetrahedra);
  ASSERT_EQ(a.positions.size(), b.positions.size());
  for (std::size_t i = 0; i < a.positions.size(); ++i) {
    EXPECT_EQ(a.positions[i], b.positions[i]) << "node " << a.node_numbers[i];
  }
}

void expectAllPositive(const core::Mesh& mesh) {
  for (const core::Tetrahedron& tet : mesh.tetrahedra) {
    EXPECT_GT(core::signedVolume(mesh.positions, tet), 0.0);
  }
}

// Reads the integer `"key": value` from a small JSON file such as mesh_info.json.
long jsonInteger(const std::string& path, const std::string& key) {
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t at = text.find("\"" + key + "\":");
  if (at == std::string::npos) {
    ADD_FAILURE() << path << " has no key " << key;
    return -1;
  }
  return std::stol(text.substr(at + key.size() + 3));
}

// --- Reference meshes ---------------------------------------------------------------------------

// All tetrahedral reference meshes that ship with .msh (2.2 and 4.1) and .node/.ele files.
class ReferenceMeshTest : public ::testing::TestWithParam<std::string> {};

TEST_P(ReferenceMeshTest, AllThreeFormatsGiveTheSameMesh) {
  const std::string prefix = kReferenceMeshes + GetParam() + "/" + GetParam();
  const MeshReadResult v22 = readGmsh(prefix + ".msh");
  const MeshReadResult v41 = readGmsh(prefix + "_v41.msh");
  const MeshReadResult tetgen = readTetGen(prefix);

  const std::string info = kReferenceMeshes + GetParam() + "/mesh_info.json";
  EXPECT_EQ(v22.mesh.numNodes(), jsonInteger(info, "nodes"));
  EXPECT_EQ(v22.mesh.numTetrahedra(), jsonInteger(info, "elements"));
  expectSameMesh(v22.mesh, v41.mesh);
  expectSameMesh(v22.mesh, tetgen.mesh);
  EXPECT_NEAR(core::totalVolume(v22.mesh), 0.01, 1e-12);
  expectAllPositive(v22.mesh);
  EXPECT_TRUE(v22.warnings.empty()) << v22.warnings.front();
  EXPECT_TRUE(v41.warnings.empty()) << v41.warnings.front();
  EXPECT_TRUE(tetgen.warnings.empty()) << tetgen.warnings.front();
}

INSTANTIATE_TEST_SUITE_P(MeshReaders, ReferenceMeshTest,
                         ::testing::Values("tetU_L1", "tetU_L2", "tetU_L3", "tetS_L1", "tetS_L2",
                                           "tetS_L3"));

TEST(MeshReadersReference, TetU1CountsAndNumbering) {
  const std::string dir = kReferenceMeshes + "tetU_L1/";
  const MeshReadResult v22 = readGmsh(dir + "tetU_L1.msh");
  const MeshReadResult v41 = readGmsh(dir + "tetU_L1_v41.msh");
  const MeshReadResult tetgen = readTetGen(dir + "tetU_L1.node");
  for (const MeshReadResult* result : {&v22, &v41, &tetgen}) {
    EXPECT_EQ(result->mesh.numNodes(), 86);
    EXPECT_EQ(result->mesh.numTetrahedra(), 197);
    EXPECT_NEAR(core::totalVolume(result->mesh), 0.01, 1e-12);
  }
  expectSameMesh(v22.mesh, v41.mesh);
  expectSameMesh(v22.mesh, tetgen.mesh);

  // File numbers are kept (1-based here), and the first tetrahedron is "1 82 72 27 53".
  EXPECT_EQ(v22.mesh.node_numbers.front(), 1);
  EXPECT_EQ(v22.mesh.node_numbers.back(), 86);
  EXPECT_EQ(v22.mesh.tetrahedra.front(), (core::Tetrahedron{81, 71, 26, 52}));
  EXPECT_EQ(v22.mesh.positions[4], Eigen::Vector3d(1.0, -0.05, 0.05));  // node 5
}

TEST(MeshReadersReference, TetS2Counts) {
  const std::string prefix = kReferenceMeshes + "tetS_L2/tetS_L2";
  for (const std::string& path : {prefix + ".msh", prefix + "_v41.msh", prefix + ".ele"}) {
    const MeshReadResult result = readMesh(path);
    EXPECT_EQ(result.mesh.numNodes(), 189) << path;
    EXPECT_EQ(result.mesh.numTetrahedra(), 480) << path;
    EXPECT_NEAR(core::totalVolume(result.mesh), 0.01, 1e-12) << path;
  }
}

TEST(MeshReadersReference, HexahedralMeshReadsTheSameFromBothVersions) {
  const std::string prefix = kReferenceMeshes + "hex_L2/hex_L2";
  const MeshReadResult v22 = readMesh(prefix + ".msh");
  const MeshReadResult v41 = readMesh(prefix + "_v41.msh");
  for (const MeshReadResult* result : {&v22, &v41}) {
    EXPECT_TRUE(result->warnings.empty());
    EXPECT_EQ(result->mesh.numNodes(), 189);  // the same nodes as tetS_L2
    EXPECT_EQ(result->mesh.numTetrahedra(), 0);
    ASSERT_EQ(result->mesh.cells.size(), 80u);
    for (const core::Cell& cell : result->mesh.cells) {
      EXPECT_EQ(cell.type, core::CellType::kHexahedron);
    }
    EXPECT_NEAR(core::totalVolume(result->mesh), 0.01, 1e-15);
  }
  EXPECT_EQ(v22.mesh.positions, v41.mesh.positions);
  for (size_t c = 0; c < 80; ++c) EXPECT_EQ(v22.mesh.cells[c].nodes, v41.mesh.cells[c].nodes);
}

// --- Hand-written meshes ------------------------------------------------------------------------

TEST(MeshReadersTetGen, ZeroBasedNumbering) {
  const std::string prefix = kTestMeshes + "two_tets_0based";
  const MeshReadResult result = readTetGen(prefix);
  EXPECT_TRUE(result.warnings.empty());
  EXPECT_EQ(result.mesh.node_numbers, (std::vector<long>{0, 1, 2, 3, 4}));
  EXPECT_EQ(result.mesh.tetrahedra, (std::vector<core::Tetrahedron>{{0, 1, 2, 3}, {0, 2, 1, 4}}));
  EXPECT_EQ(result.mesh.positions[4], Eigen::Vector3d(0.0, 0.0, -1.0));
  EXPECT_NEAR(core::totalVolume(result.mesh), 1.0 / 3.0, 1e-15);

  // The prefix, either file and readMesh all name the same pair.
  for (const std::string& path : {prefix + ".node", prefix + ".ele"}) {
    expectSameMesh(readTetGen(path).mesh, result.mesh);
    expectSameMesh(readMesh(path).mesh, result.mesh);
  }
  expectSameMesh(readMesh(prefix).mesh, result.mesh);
}

// repair_v22.msh and repair_v41.msh hold the same mesh: nodes 10..50 form two tetrahedra,
// element 8 (10 20 30 50) is inverted, node 60 is used only by a point element.
void expectRepairedMesh(const MeshReadResult& result, const std::string& path) {
  SCOPED_TRACE(path);
  EXPECT_EQ(result.mesh.node_numbers, (std::vector<long>{10, 20, 30, 40, 50}));
  EXPECT_EQ(result.mesh.positions[1], Eigen::Vector3d(1.0, 0.0, 0.0));
  EXPECT_EQ(result.mesh.positions[4], Eigen::Vector3d(0.0, 0.0, -1.0));
  // Element 8 keeps its first two nodes and has the last two swapped.
  EXPECT_EQ(result.mesh.tetrahedra, (std::vector<core::Tetrahedron>{{0, 1, 2, 3}, {0, 1, 4, 2}}));
  expectAllPositive(result.mesh);
  EXPECT_NEAR(core::totalVolume(result.mesh), 1.0 / 3.0, 1e-15);

  ASSERT_EQ(result.warnings.size(), 2u);
  EXPECT_TRUE(containsAll(result.warnings[0], {path, "dropped 1 node", "60"}));
  EXPECT_TRUE(
      containsAll(result.warnings[1], {path, "1 element listed in mirrored order", "element 8"}));
  EXPECT_EQ(result.warnings[1].find("element 7"), std::string::npos);
}

TEST(MeshReadersGmsh, Version22RepairsInvertedElementAndDropsUnusedNode) {
  const std::string path = kTestMeshes + "repair_v22.msh";
  expectRepairedMesh(readGmsh(path), path);
}

TEST(MeshReadersGmsh, Version41RepairsInvertedElementAndDropsUnusedNode) {
  // Also: nodes in four entity blocks, some with parametric coordinates, first block unused.
  const std::string path = kTestMeshes + "repair_v41.msh";
  expectRepairedMesh(readGmsh(path), path);
  expectRepairedMesh(readMesh(path), path);
}

// The stream overloads read what the file readers read, and name the stream in every message.
TEST(MeshReadersStreams, SameMeshAsFromTheFiles) {
  for (const char* name : {"repair_v22.msh", "repair_v41.msh"}) {
    std::ifstream file(kTestMeshes + name);
    const MeshReadResult result = readGmsh(file, name);
    expectSameMesh(result.mesh, readGmsh(kTestMeshes + name).mesh);
    expectRepairedMesh(result, name);
  }
  const std::string prefix = kTestMeshes + "two_tets_0based";
  std::ifstream nodes(prefix + ".node");
  std::ifstream elements(prefix + ".ele");
  expectSameMesh(readTetGen(nodes, elements, "two_tets").mesh, readTetGen(prefix).mesh);

  std::istringstream text("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 x\n");
  EXPECT_TRUE(containsAll(errorOf([&] { readGmsh(text, "in memory"); }),
                          {"in memory, line 6", "node 1", "'x'"}));
  std::istringstream node_text("4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n");
  std::istringstream element_text("1 4 0\n1 1 2 3 9\n");
  EXPECT_TRUE(containsAll(errorOf([&] { readTetGen(node_text, element_text, "in_memory"); }),
                          {"in_memory.ele, line 2", "node 9", "in_memory.node"}));
}

// --- Malformed files ----------------------------------------------------------------------------

// Writes small files into a fresh directory that is removed after each test.
class MalformedMeshTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("deformable_sim_mesh_readers_" + std::to_string(getpid()) + "_" + test->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) const {
    const std::string path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }

  fs::path dir_;
};

// Lines 1-3 of a 2.2 file, then lines 4-10 with four nodes of a unit tetrahedron.
const std::string kFormat22 = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
const std::string kNodes22 = "$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n";

TEST_F(MalformedMeshTest, UnknownNodeReference) {
  const std::string path = write(
      "unknown.msh", kFormat22 + kNodes22 + "$Elements\n1\n5 4 2 1 1 1 2 3 9\n$EndElements\n");
  EXPECT_TRUE(containsAll(errorOf([&] { readGmsh(path); }),
                          {path, "line 13", "element 5", "node 9", "not defined"}));
}

TEST_F(MalformedMeshTest, RepeatedNodeInElement) {
  const std::string path = write(
      "repeated.msh", kFormat22 + kNodes22 + "$Elements\n1\n5 4 2 1 1 1 2 2 3\n$EndElements\n");
  EXPECT_TRUE(containsAll(errorOf([&] { readGmsh(path); }),
                          {path, "line 13", "element 5", "node 2 more than once"}));
}

TEST_F(MalformedMeshTest, DuplicateNodeNumber) {
  const std::string node =
      write("dup.node", "5 3 0 0\n1 0 0 0\n2 1 0 0\n2 0 1 0\n3 0 0 1\n4 1 1 1\n");
  write("dup.ele", "1 4 0\n1 1 2 3 4\n");
  EXPECT_TRUE(containsAll(errorOf([&] { readTetGen(node); }),
                          {node, "line 4", "duplicate node number 2", "line 3"}));
}

TEST_F(MalformedMeshTest, ZeroVolumeElement) {
  // 4.1: the four nodes lie in the plane z = 0.
  const std::string path = write("flat.msh",
                                 "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
                                 "$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n"
                                 "0 0 0\n1 0 0\n0 1 0\n1 1 0\n$EndNodes\n"
                                 "$Elements\n1 1 5 5\n3 1 4 1\n5 1 2 3 4\n$EndElements\n");
  EXPECT_TRUE(
      containsAll(errorOf([&] { readGmsh(path); }), {path, "line 19", "element 5", "zero volume"}));
}

TEST_F(MalformedMeshTest, DegeneracyToleranceIsRelativeToElementSize) {
  // A valid tetrahedron 1e-4 m across (6V = 1e-12 m^3) is kept; one flattened to a height of
  // 1e-13 of its size is rejected.
  write("small.node", "4 3 0 0\n1 0 0 0\n2 1e-4 0 0\n3 0 1e-4 0\n4 0 0 1e-4\n");
  write("small.ele", "1 4 0\n1 1 2 3 4\n");
  EXPECT_NEAR(core::totalVolume(readTetGen((dir_ / "small").string()).mesh), 1e-12 / 6, 1e-24);

  write("sliver.node", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1e-13\n");
  write("sliver.ele", "1 4 0\n1 1 2 3 4\n");
  const std::string ele = (dir_ / "sliver.ele").string();
  EXPECT_TRUE(
      containsAll(errorOf([&] { readTetGen(ele); }), {ele, "line 2", "element 1", "zero volume"}));
}

TEST_F(MalformedMeshTest, SliversAreKeptWithAWarningNamingThem) {
  // Element 7 is the unit corner tetrahedron; element 9 shares its base and has its apex 1e-4
  // above it, far enough from zero volume (1e-12) to be kept, but a sliver.
  write("slivers.node", "5 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 0.3 0.3 -1e-4\n");
  write("slivers.ele", "2 4 0\n7 1 2 3 4\n9 1 3 2 5\n");
  const std::string ele = (dir_ / "slivers.ele").string();
  const MeshReadResult read = readTetGen(ele);
  ASSERT_EQ(read.mesh.numTetrahedra(), 2);
  ASSERT_EQ(read.warnings.size(), 1u);
  EXPECT_TRUE(containsAll(read.warnings[0], {ele, "1 sliver tetrahedron", "element 9"}));
  EXPECT_EQ(read.warnings[0].find("element 7"), std::string::npos);
  EXPECT_EQ(core::sliverTetrahedra(read.mesh), std::vector<int>{1});
}

TEST_F(MalformedMeshTest, NanCoordinate) {
  const std::string path =
      write("nan.msh", kFormat22 + "$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 nan 0\n4 0 0 1\n$EndNodes\n" +
                           "$Elements\n1\n1 4 0 1 2 3 4\n$EndElements\n");
  EXPECT_TRUE(containsAll(errorOf([&] { readGmsh(path); }),
                          {path, "line 8", "node 3", "not a finite number"}));

  const std::string node = write("inf.node", "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 -inf\n");
  write("inf.ele", "1 4 0\n0 0 1 2 3\n");
  EXPECT_TRUE(containsAll(errorOf([&] { readTetGen(node); }),
                          {node, "line 5", "node 3", "not a finite number"}));
}

TEST_F(MalformedMeshTest, TruncatedFile) {
  // The $Elements header announces two elements; the file ends after the first.
  const std::string path =
      write("truncated.msh", kFormat22 + kNodes22 + "$Elements\n2\n1 4 0 1 2 3 4\n");
  EXPECT_TRUE(
      containsAll(errorOf([&] { readGmsh(path); }),
                  {path, "line 13", "ends inside the $Elements section", "element 2 of 2"}));

  // A node line cut short.
  const std::string cut =
      write("cut.msh", kFormat22 + "$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0");
  EXPECT_TRUE(
      containsAll(errorOf([&] { readGmsh(cut); }), {cut, "line 9", "node 4", "expected 4 values"}));

  // A TetGen .node file with fewer nodes than its header says.
  const std::string node = write("short.node", "# comment\n5 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n");
  write("short.ele", "1 4 0\n1 1 2 3 4\n");
  EXPECT_TRUE(containsAll(errorOf([&] { readTetGen(node); }),
                          {node, "line 5", "3 of the 5 nodes announced on line 2", "node 4 of 5"}));
}

TEST_F(MalformedMeshTest, CellsAreReadMirroredOnesReorderedTangledOnesRefused) {
  // A unit cube and a pyramid on its top face (apex node 9), after a triangle that is skipped.
  const std::string nodes =
      "$Nodes\n9\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n"
      "5 0 0 1\n6 1 0 1\n7 1 1 1\n8 0 1 1\n9 0.5 0.5 1.5\n$EndNodes\n";
  auto mesh_with = [&](const std::string& name, const std::string& hex) {
    return write(name, kFormat22 + nodes + "$Elements\n3\n11 2 2 0 1 1 2 3\n12 5 2 0 1 " + hex +
                           "\n13 7 2 0 1 5 6 7 8 9\n$EndElements\n");
  };
  const MeshReadResult good = readGmsh(mesh_with("cube.msh", "1 2 3 4 5 6 7 8"));
  EXPECT_TRUE(good.warnings.empty());
  ASSERT_EQ(good.mesh.cells.size(), 2u);
  EXPECT_EQ(good.mesh.cells[1].type, core::CellType::kPyramid);
  EXPECT_NEAR(core::totalVolume(good.mesh), 1.0 + 1.0 / 6.0, 1e-15);
  // The shared face is interior: five squares of the cube and four triangles of the pyramid.
  EXPECT_EQ(core::extractBoundary(good.mesh).size(), 9u);

  const std::string path = mesh_with("mirrored.msh", "5 6 7 8 1 2 3 4");
  const MeshReadResult mirrored = readGmsh(path);
  ASSERT_EQ(mirrored.warnings.size(), 1u);
  EXPECT_TRUE(
      containsAll(mirrored.warnings[0], {path, "1 element listed in mirrored order", "12"}));
  EXPECT_NEAR(core::totalVolume(mirrored.mesh), 1.0 + 1.0 / 6.0, 1e-15);

  const std::string tangled = mesh_with("tangled.msh", "2 1 3 4 5 6 7 8");
  EXPECT_TRUE(containsAll(errorOf([&] { readGmsh(tangled); }),
                          {tangled, "line 19", "element 12 (nodes 2 1 3 4 5 6 7 8)", "tangled"}));

  // Second-order elements are refused, naming what is supported.
  const std::string quadratic =
      write("quadratic.msh",
            kFormat22 + nodes + "$Elements\n1\n12 11 2 0 1 1 2 3 4 5 6 7 8 9 1\n$EndElements\n");
  EXPECT_TRUE(containsAll(errorOf([&] { readGmsh(quadratic); }),
                          {quadratic, "line 18", "10-node second order tetrahedron",
                           "not supported yet", "8-node hexahedra, 5"}));

  const std::string ele = (dir_ / "quadratic.ele").string();
  write("quadratic.node", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n");
  write("quadratic.ele", "1 10 0\n1 1 2 3 4 1 2 3 4 1 2\n");
  EXPECT_TRUE(containsAll(errorOf([&] { readTetGen(ele); }), {ele, "line 1", "10-node"}));
}

TEST_F(MalformedMeshTest, MissingFile) {
  const std::string msh = (dir_ / "absent.msh").string();
  EXPECT_TRUE(containsAll(errorOf([&] { readGmsh(msh); }), {msh, "No such file"}));
  EXPECT_TRUE(containsAll(errorOf([&] { readMesh(msh); }), {msh}));

  const std::string prefix = (dir_ / "absent").string();
  EXPECT_TRUE(containsAll(errorOf([&] { readTetGen(prefix); }), {prefix + ".node"}));

  // A present .node with a missing .ele names the .ele.
  write("half.node", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n");
  const std::string ele = (dir_ / "half.ele").string();
  EXPECT_TRUE(containsAll(errorOf([&] { readMesh((dir_ / "half.node").string()); }), {ele}));

  EXPECT_TRUE(containsAll(errorOf([&] { readGmsh(dir_.string()); }), {dir_.string(), "directory"}));
}

TEST_F(MalformedMeshTest, UnsupportedFormats) {
  const std::string binary = write("binary.msh", "$MeshFormat\n2.2 1 8\n");
  EXPECT_TRUE(containsAll(errorOf([&] { readGmsh(binary); }), {binary, "line 2", "binary"}));

  const std::string v30 = write("v30.msh", "$MeshFormat\n3.0 0 8\n$EndMeshFormat\n");
  EXPECT_TRUE(
      containsAll(errorOf([&] { readGmsh(v30); }), {v30, "line 2", "version 3.0", "2.2 and 4.1"}));

  const std::string other = write("other.msh", "hello\n");
  EXPECT_TRUE(containsAll(errorOf([&] { readGmsh(other); }), {other, "line 1", "$MeshFormat"}));

  const std::string vtk = write("mesh.vtk", "");
  EXPECT_TRUE(containsAll(errorOf([&] { readMesh(vtk); }), {vtk, "unknown extension '.vtk'"}));
}

TEST_F(MalformedMeshTest, CountsThatDoNotMatch) {
  // The $Nodes header says 3, four nodes follow.
  const std::string extra = write(
      "extra.msh", kFormat22 + "$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n" + "4 0 0 1\n$EndNodes\n");
  EXPECT_TRUE(
      containsAll(errorOf([&] { readGmsh(extra); }),
                  {extra, "line 9", "expected $EndNodes after the 3 nodes announced on line 5"}));

  // 4.1: the header says 5 nodes, the only block holds 4.
  const std::string blocks = write("blocks.msh",
                                   "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
                                   "$Nodes\n1 5 1 5\n3 1 0 4\n1\n2\n3\n4\n"
                                   "0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n");
  EXPECT_TRUE(containsAll(errorOf([&] { readGmsh(blocks); }),
                          {blocks, "line 14", "hold 4 nodes", "announces 5"}));

  // TetGen: more elements than the header announces.
  write("more.node", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n");
  const std::string more = write("more.ele", "1 4 0\n1 1 2 3 4\n\n2 1 2 4 3\n");
  EXPECT_TRUE(
      containsAll(errorOf([&] { readTetGen(more); }),
                  {more, "line 4", "element 2", "more elements than the 1 announced on line 1"}));
}

TEST_F(MalformedMeshTest, MalformedValues) {
  // Letter O instead of zero.
  const std::string letter =
      write("letter.msh", kFormat22 + "$Nodes\n4\n1 0 0 0\n2 1 O 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n");
  EXPECT_TRUE(containsAll(errorOf([&] { readGmsh(letter); }),
                          {letter, "line 7", "node 2", "y coordinate", "'O'"}));

  // A TetGen element with three nodes (and a comment, which does not count).
  write("three.node", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n");
  const std::string three = write("three.ele", "1 4 0\n7 1 2 3 # 4\n");
  EXPECT_TRUE(containsAll(errorOf([&] { readTetGen(three); }),
                          {three, "line 2", "element 7", "expected 5 values", "found 4"}));

  // 2.2 element whose node count does not fit its type.
  const std::string short_tet = write(
      "short_tet.msh", kFormat22 + kNodes22 + "$Elements\n1\n3 4 2 1 1 1 2 3\n$EndElements\n");
  EXPECT_TRUE(containsAll(errorOf([&] { readGmsh(short_tet); }),
                          {short_tet, "line 13", "element 3", "4-node tetrahedron"}));
}

TEST_F(MalformedMeshTest, NoVolumeElements) {
  const std::string path =
      write("surface.msh", kFormat22 + kNodes22 + "$Elements\n1\n1 2 2 0 1 1 2 3\n$EndElements\n");
  EXPECT_TRUE(containsAll(errorOf([&] { readGmsh(path); }),
                          {path, "line 11", "no volume elements", "1 lower-dimensional element"}));

  write("empty.node", "# nothing\n0 3 0 0\n");
  const std::string ele = write("empty.ele", "0 4 0\n");
  EXPECT_TRUE(
      containsAll(errorOf([&] { readTetGen(ele); }), {ele, "line 1", "no volume elements"}));
}

TEST_F(MalformedMeshTest, ManyUnusedNodesGiveOneWarningWithACount) {
  std::string nodes = "$Nodes\n12\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n";
  for (int n = 5; n <= 12; ++n) nodes += std::to_string(n) + " 5 5 5\n";
  const std::string path = write(
      "unused.msh", kFormat22 + nodes + "$EndNodes\n$Elements\n1\n1 4 0 1 2 3 4\n$EndElements\n");
  const MeshReadResult result = readGmsh(path);
  EXPECT_EQ(result.mesh.numNodes(), 4);
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_TRUE(containsAll(result.warnings[0], {path, "dropped 8 nodes", "5, 6, 7, 8, 9, ..."}));
}

}  // namespace
}  // namespace deformable_sim::io
