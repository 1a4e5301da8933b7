// `rosrun sap_broadphase node`: the broad phase as a ROS node.
#include <ros/ros.h>

#include "sap_broadphase/ros/node.h"
#include "sap_broadphase/ros/node_params.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "sap_broadphase");
  ros::NodeHandle node;
  ros::NodeHandle private_node("~");
  sap_broadphase::NodeParams params;
  const std::string error = sap_broadphase::loadNodeParams(private_node, params);
  if (!error.empty()) {
    ROS_FATAL("%s", error.c_str());
    return 1;
  }
  sap_broadphase::BroadphaseNode broadphase(node, params);
  ros::spin();
  return 0;
}
