// Collision geometry from a URDF: primitives and meshes (plain, file:// and package:// file
// names, with their scale); a mesh that cannot be read is skipped with a warning.
#include <gtest/gtest.h>

#include <string>

#include "deformable_sim/io/urdf_shapes.h"

namespace dio = deformable_sim::io;
namespace dc = deformable_sim::core;

namespace {

const std::string kMeshes = DEFORMABLE_SIM_SOURCE_DIR "/test/data/meshes";

std::string robot(const std::string& finger_geometry) {
  return R"(<robot name="gripper">
  <link name="palm"><collision><geometry><box size="0.1 0.1 0.02"/></geometry></collision></link>
  <link name="finger">
    <collision>
      <origin xyz="0 0 0.1" rpy="0 0 0"/>
      <geometry>)" +
         finger_geometry + R"(</geometry>
    </collision>
  </link>
  <joint name="j" type="fixed"><parent link="palm"/><child link="finger"/></joint>
</robot>)";
}

}  // namespace

TEST(UrdfShapes, MeshCollisionGeometryBecomesAMeshShape) {
  const dio::PackageResolver resolver = [](const std::string& uri) {
    const std::string prefix = "package://test_meshes/";
    return uri.rfind(prefix, 0) == 0 ? kMeshes + "/" + uri.substr(prefix.size()) : "";
  };
  const std::vector<std::string> filenames = {"cube_ascii.stl",
                                              "file://" + kMeshes + "/cube_binary.stl",
                                              "package://test_meshes/cube.obj", "cube_cm.dae"};
  for (const std::string& filename : filenames) {
    std::vector<std::string> warnings;
    const auto shapes = dio::readCollisionShapes(
        robot("<mesh filename=\"" + filename + "\" scale=\"0.02 0.02 0.1\"/>"), &warnings, resolver,
        kMeshes);
    EXPECT_TRUE(warnings.empty()) << filename << ": " << warnings.front();
    const std::vector<dc::PlacedShape>& finger = dio::linkShapes(shapes, "finger");
    ASSERT_EQ(finger.size(), 1u) << filename;
    EXPECT_EQ(finger[0].name, "finger");
    ASSERT_EQ(finger[0].shape.kind, dc::Shape::Kind::kMesh) << filename;
    EXPECT_TRUE(finger[0].pose.translation().isApprox(Eigen::Vector3d(0, 0, 0.1)));
    // A 2 cm x 2 cm x 10 cm finger: 1 cm from its axis to its side.
    EXPECT_NEAR(dc::signedDistance(finger[0].shape, {0.0, 0.0, 0.0}), -0.01, 1e-9) << filename;
    EXPECT_NEAR(dc::signedDistance(finger[0].shape, {0.03, 0.0, 0.0}), 0.02, 1e-9) << filename;
  }
}

TEST(UrdfShapes, AMeshThatCannotBeReadIsSkippedWithAWarning) {
  std::vector<std::string> warnings;
  const auto shapes = dio::readCollisionShapes(
      robot("<mesh filename=\"package://nowhere/finger.stl\"/>"), &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("link 'finger': collision mesh 'package://nowhere/finger.stl'"),
            std::string::npos)
      << warnings[0];
  EXPECT_EQ(dio::linkShapes(shapes, "palm").size(), 1u);
  EXPECT_THROW(dio::linkShapes(shapes, "finger"), dio::UrdfError);
}
