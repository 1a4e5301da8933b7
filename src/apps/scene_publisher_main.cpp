// `rosrun sap_broadphase scene_publisher`: the paper's scenes as BoxArray frames on `boxes`.
#include <string>

#include <ros/ros.h>

#include "scene_publisher.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "scene_publisher");
  ros::NodeHandle node;
  ros::NodeHandle private_node("~");
  sap_broadphase::ScenePublisherParams params;
  const std::string error = sap_broadphase::loadScenePublisherParams(private_node, params);
  if (!error.empty()) {
    ROS_FATAL("%s", error.c_str());
    return 1;
  }
  sap_broadphase::ScenePublisher publisher(node, params);
  publisher.waitUntilDone();
  return 0;
}
