// `rosrun sap_broadphase scene_publisher`: the paper's scenes as BoxArray frames on `boxes`.
#include <string>

#include <ros/ros.h>

#include "sap_broadphase/BoxArray.h"
#include "sap_broadphase/core/scenes.h"
#include "sap_broadphase/ros/conversions.h"

namespace {

/// Reads the scene parameters; returns the problem or an empty string.
std::string loadSceneConfig(const ros::NodeHandle& inPrivate,
                            sap_broadphase::SceneConfig& outConfig) {
  std::string scene = "uniform";
  inPrivate.param<std::string>("scene", scene, scene);
  if (!sap_broadphase::parseSceneKind(scene, outConfig.kind))
    return "~scene must be uniform, ball or plane, not '" + scene + "'";
  int count = static_cast<int>(outConfig.n);
  inPrivate.param("n", count, count);
  if (count < 0) return "~n must not be negative";
  outConfig.n = static_cast<std::size_t>(count);
  inPrivate.param("density", outConfig.density, outConfig.density);
  int seed = static_cast<int>(outConfig.seed);
  inPrivate.param("seed", seed, seed);
  outConfig.seed = static_cast<uint64_t>(seed);
  inPrivate.param("plane_axis", outConfig.plane_axis, outConfig.plane_axis);
  if (outConfig.plane_axis < 0 || outConfig.plane_axis > 2) return "~plane_axis must be 0, 1 or 2";
  inPrivate.param("scene_frames", outConfig.frames, outConfig.frames);
  if (outConfig.frames < 1) return "~scene_frames must be at least 1";
  inPrivate.param("speed", outConfig.speed, outConfig.speed);
  return "";
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "scene_publisher");
  ros::NodeHandle node;
  ros::NodeHandle private_node("~");
  sap_broadphase::SceneConfig config;
  config.n = 10000;
  const std::string error = loadSceneConfig(private_node, config);
  if (!error.empty()) {
    ROS_FATAL("%s", error.c_str());
    return 1;
  }
  double rate_hz = 10.0;
  private_node.param("rate", rate_hz, rate_hz);
  int max_frames = 0;
  private_node.param("max_frames", max_frames, max_frames);
  std::string frame_id = "map";
  private_node.param<std::string>("frame_id", frame_id, frame_id);
  if (!(rate_hz > 0.0)) {
    ROS_FATAL("~rate must be positive");
    return 1;
  }

  ros::Publisher publisher = node.advertise<sap_broadphase::BoxArray>("boxes", 2);
  sap_broadphase::SceneSimulator simulator(config);
  sap_broadphase::BoxArray msg;
  msg.header.frame_id = frame_id;
  ros::Rate rate(rate_hz);
  for (int published = 0; ros::ok() && (max_frames <= 0 || published < max_frames); ++published) {
    // Ball and plane scenes are timed for ~scene_frames frames; start over after that.
    if (simulator.frame() >= config.frames) simulator = sap_broadphase::SceneSimulator(config);
    msg.header.stamp = ros::Time::now();
    sap_broadphase::boxSetToBoxArray(simulator.boxes(), msg.header, msg);
    msg.ids.clear();  // the scene numbers its boxes 0..n-1: the message's default
    publisher.publish(msg);
    simulator.step();
    ros::spinOnce();
    rate.sleep();
  }
  return 0;
}
