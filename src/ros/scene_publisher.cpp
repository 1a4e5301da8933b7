// ScenePublisher: parameters, the publishing thread and message reuse.
#include "scene_publisher.h"

#include <algorithm>

#include <boost/make_shared.hpp>

#include "sap_broadphase/ros/conversions.h"

namespace sap_broadphase {

namespace {

/// Reads the scene's own parameters; returns the problem or an empty string.
std::string loadSceneConfig(const ros::NodeHandle& inPrivate, SceneConfig& outConfig) {
  std::string scene = "uniform";
  inPrivate.param<std::string>("scene", scene, scene);
  if (!parseSceneKind(scene, outConfig.kind))
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

std::string loadScenePublisherParams(const ros::NodeHandle& inPrivate,
                                     ScenePublisherParams& outParams) {
  const std::string error = loadSceneConfig(inPrivate, outParams.scene);
  if (!error.empty()) return error;
  inPrivate.param("rate", outParams.rate_hz, outParams.rate_hz);
  if (!(outParams.rate_hz > 0.0)) return "~rate must be positive";
  inPrivate.param("max_frames", outParams.max_frames, outParams.max_frames);
  inPrivate.param<std::string>("frame_id", outParams.frame_id, outParams.frame_id);
  return "";
}

ScenePublisher::ScenePublisher(ros::NodeHandle& ioNode, const ScenePublisherParams& inParams)
    : params_(inParams), simulator_(inParams.scene) {
  publisher_ = ioNode.advertise<BoxArray>("boxes", 2);
  thread_ = std::thread(&ScenePublisher::publishLoop, this);
}

ScenePublisher::~ScenePublisher() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void ScenePublisher::waitUntilDone() {
  if (thread_.joinable()) thread_.join();
}

void ScenePublisher::publishLoop() {
  using Clock = std::chrono::steady_clock;
  const auto period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(1.0 / params_.rate_hz));
  Clock::time_point next_frame_at = Clock::now();
  for (int published = 0; ros::ok() && (params_.max_frames <= 0 || published < params_.max_frames);
       ++published) {
    // Ball and plane scenes are timed for ~scene_frames frames; start over after that.
    if (simulator_.frame() >= params_.scene.frames) simulator_ = SceneSimulator(params_.scene);
    BoxArrayPtr msg = freeMessage();
    msg->header.frame_id = params_.frame_id;
    msg->header.stamp = ros::Time::now();
    boxSetToBoxArray(simulator_.boxes(), msg->header, *msg);
    msg->ids.clear();  // the scene numbers its boxes 0..n-1: the message's default
    publisher_.publish(msg);
    simulator_.step();
    // As ros::Rate: a frame that overran its period starts the next period now, no burst.
    next_frame_at = std::max(next_frame_at + period, Clock::now());
    if (!sleepUntil(next_frame_at)) return;
  }
}

BoxArrayPtr ScenePublisher::freeMessage() {
  // Only this thread holds message_ once roscpp's queues and every in-process subscriber let go
  // of it; nobody can take a new reference after that, so it can be written again.
  if (!message_ || message_.use_count() > 1) message_ = boost::make_shared<BoxArray>();
  return message_;
}

bool ScenePublisher::sleepUntil(std::chrono::steady_clock::time_point inWakeAt) {
  std::unique_lock<std::mutex> lock(mutex_);
  return !wake_.wait_until(lock, inWakeAt, [this] { return stopping_; });
}

}  // namespace sap_broadphase
