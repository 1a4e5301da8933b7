// `rosrun sap_broadphase node`: the broad phase as a ROS node.
#include <csignal>

#include <ros/ros.h>

#include "node.h"
#include "node_params.h"

namespace {

/// SIGTERM (systemd, docker stop, roslaunch's escalation) ends the node as SIGINT does:
/// ros::spin() returns and ros::shutdown() unregisters from the master. Without it the
/// process dies at once and the master lists the node until `rosnode cleanup`.
/// ros::requestShutdown() only sets a flag, as roscpp's own SIGINT handler does.
void onTerminate(int) {
  ros::requestShutdown();
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "sap_broadphase");
  std::signal(SIGTERM, onTerminate);
  ros::NodeHandle node;
  ros::NodeHandle private_node("~");
  sap_broadphase::NodeParams params;
  const std::string error = sap_broadphase::loadNodeParams(private_node, params);
  if (!error.empty()) {
    ROS_FATAL("%s", error.c_str());
    return 1;
  }
  {
    sap_broadphase::BroadphaseNode broadphase(node, private_node, params);
    ros::spin();
  }
  ros::shutdown();
  return 0;
}
