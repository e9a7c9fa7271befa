// The core (and the readers, and the fit) must build without ROS: no header or source there
// includes one.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

namespace fs = std::filesystem;

TEST(RosFree, NoCoreOrIoFileIncludesARosHeader) {
  const std::regex ros_include(
      R"(#\s*include\s*[<"](ros/|roscpp|tf2_ros/|tf2/|rosbag/|[a-z_]+_msgs/|dynamic_reconfigure/|diagnostic_updater/))");
  int files = 0;
  for (const char* folder : {"include/deformable_sim/core", "src/core", "include/deformable_sim/io",
                             "src/io", "include/deformable_sim/identify", "src/identify"}) {
    const fs::path dir = fs::path(DEFORMABLE_SIM_SOURCE_DIR) / folder;
    ASSERT_TRUE(fs::is_directory(dir)) << dir;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
      if (!entry.is_regular_file()) continue;
      ++files;
      std::ifstream in(entry.path());
      std::string line;
      for (int number = 1; std::getline(in, line); ++number) {
        EXPECT_FALSE(std::regex_search(line, ros_include))
            << entry.path().string() << ":" << number << " includes a ROS header: " << line;
      }
    }
  }
  EXPECT_GT(files, 10);
}
