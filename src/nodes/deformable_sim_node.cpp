// deformable_sim_node: deformable bodies a ROS user drives with topics and watches in rviz.
// Parameters, topics and services: README.md, or deformable_sim_node --help.
#include <ros/ros.h>

#include <csignal>
#include <cstdio>
#include <cstring>

#include "deformable_sim/ros/node_parameters.h"
#include "deformable_sim/ros/sim_node.h"

namespace {

volatile std::sig_atomic_t stop_requested = 0;

void requestStop(int) { stop_requested = 1; }

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) {
      std::fputs(deformable_sim::ros_layer::kNodeUsage, stdout);
      return 0;
    }
  }
  // Our own signal handler: the node clears its markers before it leaves the graph.
  ros::init(argc, argv, "deformable_sim", ros::init_options::NoSigintHandler);
  std::signal(SIGINT, requestStop);
  std::signal(SIGTERM, requestStop);
  ros::NodeHandle node;
  ros::NodeHandle private_node("~");
  try {
    deformable_sim::ros_layer::SimNode sim(node, private_node);
    ros::CallbackQueue& queue = *ros::getGlobalCallbackQueue();
    while (!stop_requested && ros::ok()) queue.callAvailable(ros::WallDuration(0.05));
    sim.shutdown();
    ros::WallDuration(0.2).sleep();  // the publishers' threads deliver the DELETEALL
  } catch (const std::exception& e) {
    ROS_FATAL("%s", e.what());
    return 1;
  }
  ros::shutdown();
  return 0;
}
