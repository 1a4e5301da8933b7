// What the rostest gtests share.
#include "ros_test_support.h"

#include <gtest/gtest.h>
#include <ros/ros.h>

namespace sap_broadphase {
namespace test {

bool pollUntil(double inSeconds, const std::function<bool()>& inReady) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(inSeconds);
  while (!inReady()) {
    if (ros::WallTime::now() >= end || !ros::ok()) return false;
    ros::WallDuration(0.05).sleep();
  }
  return true;
}

int runRosTests(int argc, char** argv, const char* inNodeName, int inSpinnerThreads) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, inNodeName);
  ros::AsyncSpinner spinner(inSpinnerThreads);
  spinner.start();
  const int result = RUN_ALL_TESTS();
  spinner.stop();
  ros::shutdown();
  return result;
}

}  // namespace test
}  // namespace sap_broadphase
