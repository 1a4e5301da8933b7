// ScenePublisher: parameters, the publishing thread and message reuse.
#include "scene_publisher.h"

#include <algorithm>
#include <type_traits>

#include <boost/make_shared.hpp>

#include "node_params.h"
#include "sap_broadphase/ros/conversions.h"

namespace sap_broadphase {

namespace {

constexpr const char* kLimitsEntry = "scene_publisher parameter";

/// Reads the number parameter ~inName into ioValue, refused outside its row of the limits table.
template <typename Value>
std::string readLimited(const ros::NodeHandle& inPrivate, const std::string& inName,
                        Value& ioValue) {
  double value = static_cast<double>(ioValue);
  const std::string error =
      readLimitedParam(inPrivate, kLimitsEntry, inName, std::is_integral_v<Value>, value);
  if (error.empty()) ioValue = static_cast<Value>(value);
  return error;
}

/// Reads the scene's own parameters; returns the problem or an empty string.
std::string loadSceneConfig(const ros::NodeHandle& inPrivate, SceneConfig& outConfig) {
  std::string scene = "uniform";
  inPrivate.param<std::string>("scene", scene, scene);
  if (!parseSceneKind(scene, outConfig.kind))
    return "~scene must be uniform, ball or plane, not '" + scene + "'";
  std::string error;
  if (!(error = readLimited(inPrivate, "n", outConfig.n)).empty()) return error;
  if (!(error = readLimited(inPrivate, "density", outConfig.density)).empty()) return error;
  if (!(error = readLimited(inPrivate, "seed", outConfig.seed)).empty()) return error;
  if (!(error = readLimited(inPrivate, "plane_axis", outConfig.plane_axis)).empty()) return error;
  if (!(error = readLimited(inPrivate, "scene_frames", outConfig.frames)).empty()) return error;
  return readLimited(inPrivate, "speed", outConfig.speed);
}

}  // namespace

std::string loadScenePublisherParams(const ros::NodeHandle& inPrivate,
                                     ScenePublisherParams& outParams) {
  std::string error = loadSceneConfig(inPrivate, outParams.scene);
  if (!error.empty()) return error;
  if (!(error = readLimited(inPrivate, "rate", outParams.rate_hz)).empty()) return error;
  if (!(error = readLimited(inPrivate, "max_frames", outParams.max_frames)).empty()) return error;
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
