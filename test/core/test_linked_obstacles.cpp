// Obstacles attached to frames: placed with them, held where they were when a frame is lost.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "deformable_sim/core/driver/linked_obstacles.h"

namespace deformable_sim::core {
namespace {

TEST(LinkedObstacles, PlaceShapesWithTheirFramesAndWaitForEveryFrame) {
  PlacedShape floor;
  floor.name = "floor";
  PlacedShape finger;
  finger.name = "finger";
  finger.pose.translation() = Eigen::Vector3d(0.0, 0.0, 0.1);  // in the link's frame
  LinkedObstacles obstacles({floor});
  obstacles.attach("link", finger);
  std::optional<Eigen::Isometry3d> link;
  const auto pose = [&link](const std::string&) { return link; };
  EXPECT_FALSE(obstacles.place(pose));  // never placed yet: no stepping
  link = Eigen::Isometry3d::Identity();
  link->translation() = Eigen::Vector3d(1.0, 0.0, 0.0);
  std::optional<std::vector<PlacedShape>> placed = obstacles.place(pose);
  ASSERT_TRUE(placed && placed->size() == 2u);
  EXPECT_EQ((*placed)[0].name, "floor");
  EXPECT_TRUE((*placed)[1].pose.translation().isApprox(Eigen::Vector3d(1.0, 0.0, 0.1)));
  link.reset();  // tf lost the link: it stays where it was
  placed = obstacles.place(pose);
  ASSERT_TRUE(placed);
  EXPECT_TRUE((*placed)[1].pose.translation().isApprox(Eigen::Vector3d(1.0, 0.0, 0.1)));
}

}  // namespace
}  // namespace deformable_sim::core
