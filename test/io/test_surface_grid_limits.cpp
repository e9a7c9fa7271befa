// A body from a surface in a scene: the key max_cells that bounds its grid, the error that names
// the key, and the progress a caller is told of.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "deformable_sim/io/mesh_reader.h"
#include "deformable_sim/io/scene_file.h"
#include "surface_test_helpers.h"

namespace dc = deformable_sim::core;
namespace dio = deformable_sim::io;
namespace dt = deformable_sim::test;
namespace fs = std::filesystem;

namespace {

constexpr const char* kMaterial =
    "    material: {youngs_modulus: 1.0e6, poisson_ratio: 0.3, density: 1000.0}\n";

class SurfaceGridLimits : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("deformable_sim_limits_" + std::to_string(getpid()));
    fs::create_directories(dir_);
    dt::writeAsciiStl(dt::sphereSurface(0.05, Eigen::Vector3d::Zero(), 12, 24),
                      (dir_ / "ball.stl").string());
  }
  void TearDown() override { fs::remove_all(dir_); }

  dc::SceneSpec scene(const std::string& mesh) const {
    return dio::parseScene("bodies:\n  - name: ball\n    mesh: " + mesh + "\n" + kMaterial,
                           "scene.yaml", dir_.string());
  }
  std::string sceneError(const std::string& mesh) const {
    try {
      scene(mesh);
    } catch (const dio::SceneError& e) {
      return e.what();
    }
    return "(no error)";
  }

  fs::path dir_;
};

}  // namespace

TEST_F(SurfaceGridLimits, MaxCellsIsReadAndChecked) {
  EXPECT_EQ(scene("{surface: ball.stl, cells: 8}").bodies[0].surface_mesh->voxels.max_cells,
            dc::kMaxBoxMeshCells);
  EXPECT_EQ(scene("{surface: ball.stl, cells: 8, max_cells: 2147483647}")
                .bodies[0]
                .surface_mesh->voxels.max_cells,
            2147483647L);
  // Past what a mesh's int indices number: refused, however much memory there is.
  EXPECT_NE(sceneError("{surface: ball.stl, cells: 8, max_cells: 5000000000}")
                .find("bodies[0].mesh.max_cells: must be <= 2147483647"),
            std::string::npos)
      << sceneError("{surface: ball.stl, cells: 8, max_cells: 5000000000}");
  EXPECT_NE(sceneError("{surface: ball.stl, cells: 8, max_cells: 0}")
                .find("bodies[0].mesh.max_cells: must be >= 1"),
            std::string::npos)
      << sceneError("{surface: ball.stl, cells: 8, max_cells: 0}");
  EXPECT_NE(sceneError("{surface: ball.stl, cells: 8, max_cells: many}").find("max_cells"),
            std::string::npos);
  EXPECT_NE(sceneError("{box: {min: [0, 0, 0], max: [1, 1, 1], cells: [1, 1, 1]}, max_cells: 9}")
                .find("only with surface"),
            std::string::npos);
}

TEST_F(SurfaceGridLimits, AGridOverTheLimitNamesTheKeyTheCellsAndTheMemory) {
  const dc::SceneSpec spec = scene("{surface: ball.stl, cells: 20, max_cells: 1000}");
  try {
    dio::readMeshes(spec, nullptr);
    FAIL() << "8000 cells accepted under max_cells 1000";
  } catch (const dio::MeshError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("scene.yaml:3: bodies[0].mesh: "), std::string::npos) << message;
    EXPECT_NE(message.find("ball.stl"), std::string::npos) << message;
    EXPECT_NE(message.find("20 x 20 x 20 = 8000 cells, more than max_cells (1000)"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find(" MB"), std::string::npos) << message;
  }
  EXPECT_EQ(
      dio::readMeshes(scene("{surface: ball.stl, cells: 20, max_cells: 8000}"), nullptr).size(),
      1u);
}

TEST_F(SurfaceGridLimits, TheCallerIsToldTheProgressOfEachBody) {
  dio::SurfaceSources sources;
  std::vector<long> done;
  sources.progress = [&](const std::string& body, long cells, long total) {
    EXPECT_EQ(body, "ball");
    EXPECT_EQ(total, 8 * 8 * 8);
    done.push_back(cells);
  };
  dio::readMeshes(scene("{surface: ball.stl, cells: 8}"), nullptr, nullptr, sources);
  ASSERT_FALSE(done.empty());
  EXPECT_EQ(done.front(), 0);
  EXPECT_EQ(done.back(), 8 * 8 * 8);
}
