#include "deformable_sim/ros/voxel_progress_log.h"

#include <ros/console.h>

#include <chrono>
#include <memory>

namespace deformable_sim::ros_layer {

std::function<void(const std::string&, long, long)> voxelProgressLog() {
  struct Shown {
    std::chrono::steady_clock::time_point start;
    int tenth = -1;
  };
  auto shown = std::make_shared<Shown>();
  return [shown](const std::string& body, long done, long total) {
    const auto now = std::chrono::steady_clock::now();
    if (done == 0) *shown = Shown{now, -1};
    const double seconds = std::chrono::duration<double>(now - shown->start).count();
    const int tenth = total > 0 ? static_cast<int>(10 * done / total) : 10;
    if (seconds < 1.0 || tenth == shown->tenth) return;
    shown->tenth = tenth;
    ROS_INFO("voxelizing body '%s': %d %% of %ld grid cells in %.1f s", body.c_str(), 10 * tenth,
             total, seconds);
  };
}

}  // namespace deformable_sim::ros_layer
