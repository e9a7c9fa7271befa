// deformable_sim_node: deformable bodies a ROS user drives with topics and watches in rviz.
// Parameters, topics and services: README.md, or deformable_sim_node --help.
#include <ros/ros.h>
#include <ros/xmlrpc_manager.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstring>

#include "deformable_sim/ros/sim_node.h"
#include "sleeping_openmp_threads.h"

namespace {

constexpr const char* kUsage =
    "usage: deformable_sim_node [__name:=NAME] [_PARAMETER:=VALUE ...]\n"
    "  Steps a scene of deformable bodies on a timer; drive it with topics and services.\n"
    "Parameters (private):\n"
    "  ~scene PATH              scene YAML (default: the built-in cantilever)\n"
    "  ~rate HZ                 each tick advances 1/rate s (default: 1/(dt substeps))\n"
    "  ~substeps N              steps per tick (default 1)\n"
    "  ~start_paused BOOL       start paused (default false)\n"
    "  ~world_frame NAME        frame of positions (default world)\n"
    "  ~frame_prefix PREFIX     prefix of body frames (default: the node's namespace)\n"
    "  ~wrench_timeout S        drop a wrench whose sender is silent this long (default 0: never)\n"
    "  ~stats_rate HZ, ~marker_rate HZ, ~strain_colour_scale S\n"
    "  ~max_force N, ~max_torque NM   wrench bounds (default: 10 x the body's weight, and that\n"
    "                           force times the body's size)\n"
    "  ~max_target_distance M   how far a fixed-node target or grasp move may be (default 10)\n"
    "  ~max_steps_per_call N    the most ~step takes in one call (default 1000)\n"
    "  ~link_delay S            robot links are placed where tf had them this long ago\n"
    "                           (default 0.05)\n"
    "Subscribes: ~wrench ~node_wrench ~fixed_nodes ~grasp\n"
    "Publishes:  ~state ~stats ~mesh ~markers ~obstacles ~applied ~scene ~reactions/<body>\n"
    "            ~grasps/<name>/wrench /tf /diagnostics\n"
    "            with contact: ~contacts, and ~contacts/<link>/wrench per robot link\n"
    "Services:   ~reset ~pause ~resume ~step ~grasp; live tuning: dynamic_reconfigure\n";

std::atomic<bool> stop_requested{false};  // lock-free: safe in a signal handler

void requestStop(int) { stop_requested = true; }

// rosnode kill, or a new node of the same name: the master's request to leave, answered as roscpp
// does, but the node leaves through the same door as on Ctrl-C.
void requestStopFromMaster(XmlRpc::XmlRpcValue&, XmlRpc::XmlRpcValue& result) {
  stop_requested = true;
  result = ros::xmlrpc::responseInt(1, "", 0);
}

}  // namespace

int main(int argc, char** argv) {
  deformable_sim::letOpenMpThreadsSleep(argv);
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) {
      std::fputs(kUsage, stdout);
      return 0;
    }
  }
  // Our own signal handler: the node clears its markers before it leaves the graph.
  ros::init(argc, argv, "deformable_sim", ros::init_options::NoSigintHandler);
  std::signal(SIGINT, requestStop);
  std::signal(SIGTERM, requestStop);
  ros::NodeHandle node;
  ros::NodeHandle private_node("~");
  ros::XMLRPCManager::instance()->unbind("shutdown");
  ros::XMLRPCManager::instance()->bind("shutdown", requestStopFromMaster);
  try {
    deformable_sim::ros_layer::SimNode sim(node, private_node);
    ros::CallbackQueue& queue = *ros::getGlobalCallbackQueue();
    while (!stop_requested && ros::ok()) queue.callAvailable(ros::WallDuration(0.05));
    sim.clearMarkers();
    ros::WallDuration(0.2).sleep();  // the publishers' threads deliver the DELETEALL
  } catch (const std::exception& e) {
    ROS_FATAL("%s", e.what());
    return 1;
  }
  ros::shutdown();
  return 0;
}
