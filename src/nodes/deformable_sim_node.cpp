// deformable_sim_node: a deformable body a ROS user drives with topics and watches in rviz.
// Parameters, topics and services: README.md.
#include <ros/ros.h>

#include "deformable_sim/ros/sim_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "deformable_sim");
  ros::NodeHandle node;
  ros::NodeHandle private_node("~");
  try {
    deformable_sim::ros_layer::SimNode sim(node, private_node);
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("%s", e.what());
    return 1;
  }
  return 0;
}
