// ScenePublisher: the paper's scenes as BoxArray frames on `boxes`, from a thread of its own,
// shared by the scene_publisher executable and ScenePublisherNodelet.
#pragma once

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

#include <ros/ros.h>

#include "sap_broadphase/BoxArray.h"
#include "sap_broadphase/core/scenes.h"

namespace sap_broadphase {

/// Everything ScenePublisher can be told through its private parameters.
struct ScenePublisherParams {
  SceneConfig scene{SceneKind::kUniform, 10000};  ///< ~scene, ~n, ~density, ~seed, ...
  double rate_hz = 10.0;                          ///< ~rate: frames per second
  int max_frames = 0;            ///< ~max_frames: stop after this many; 0 = until shut down
  std::string frame_id = "map";  ///< ~frame_id of every frame's header
};

/// Reads the private parameters of inPrivate over the defaults of ScenePublisherParams.
/// Returns the problem or an empty string.
std::string loadScenePublisherParams(const ros::NodeHandle& inPrivate,
                                     ScenePublisherParams& outParams);

/// Publishes one frame of the scene every 1 / rate seconds. Each frame is a message of its own
/// handed to roscpp as a shared pointer and never written again, so a subscriber in the same
/// process (a nodelet) receives that very message without serialisation.
class ScenePublisher {
 public:
  /// Advertises `boxes` (relative to ioNode) and starts publishing.
  ScenePublisher(ros::NodeHandle& ioNode, const ScenePublisherParams& inParams);
  /// Stops publishing (a frame being published is finished first).
  ~ScenePublisher();
  ScenePublisher(const ScenePublisher&) = delete;
  ScenePublisher& operator=(const ScenePublisher&) = delete;

  /// Blocks until ~max_frames frames were published or ROS shut down.
  void waitUntilDone();

 private:
  /// The publishing thread: one frame per period until done or stopping.
  void publishLoop();
  /// The message for the next frame: the previous one again if nobody holds it any more.
  BoxArrayPtr freeMessage();
  /// Sleeps until inWakeAt or until the destructor asks to stop; false when stopping.
  bool sleepUntil(std::chrono::steady_clock::time_point inWakeAt);

  ScenePublisherParams params_;
  ros::Publisher publisher_;
  SceneSimulator simulator_;
  BoxArrayPtr message_;  // the last frame published; reused once roscpp and subscribers let go

  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;  // guarded by mutex_
  std::thread thread_;
};

}  // namespace sap_broadphase
