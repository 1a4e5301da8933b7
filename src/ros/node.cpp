// BroadphaseNode: subscriber, worker thread, publishers and the compute_pairs service.
#include "sap_broadphase/ros/node.h"

#include <chrono>
#include <utility>

#include <visualization_msgs/MarkerArray.h>

#include "sap_broadphase/ros/conversions.h"
#include "sap_broadphase/ros/markers.h"

namespace sap_broadphase {

namespace {

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point inStart) {
  return std::chrono::duration<double, std::milli>(Clock::now() - inStart).count();
}

/// Copies the engine's account of a frame into the stats message (times are added later).
void fillEngineStats(const FrameReport& inEngine, FrameStats& outStats) {
  outStats.boxes = static_cast<uint32_t>(inEngine.boxes);
  outStats.pairs = static_cast<uint32_t>(inEngine.pairs);
  outStats.primary_axis = static_cast<uint8_t>(inEngine.primary_axis);
  outStats.secondary_axis = static_cast<uint8_t>(inEngine.secondary_axis);
  outStats.dispersion_primary = inEngine.dispersion_primary;
  outStats.dispersion_secondary = inEngine.dispersion_secondary;
  outStats.axes_swapped = inEngine.axes_swapped;
  outStats.path = framePathName(inEngine.path);
  outStats.threads = static_cast<uint32_t>(inEngine.threads);
  outStats.slabs = static_cast<uint32_t>(inEngine.slabs);
  outStats.ms_sort = inEngine.ms_keys + inEngine.ms_sort;
  outStats.ms_candidates = inEngine.ms_candidates;
  outStats.ms_pairing = inEngine.ms_pairing;
  outStats.ms_output = inEngine.ms_output;
}

}  // namespace

BroadphaseNode::BroadphaseNode(ros::NodeHandle& ioNode, const NodeParams& inParams)
    : params_(inParams), service_engine_(inParams.engine), engine_(inParams.engine) {
  pairs_pub_ = ioNode.advertise<PairArray>("pairs", params_.pairs_queue_size);
  stats_pub_ = ioNode.advertise<FrameStats>("stats", 10);
  if (params_.publish_markers)
    markers_pub_ = ioNode.advertise<visualization_msgs::MarkerArray>("markers", 1);

  worker_ = std::thread(&BroadphaseNode::workerLoop, this);

  ros::AdvertiseServiceOptions service_options;
  service_options.init<ComputePairs::Request, ComputePairs::Response>(
      ioNode.resolveName("compute_pairs"),
      [this](ComputePairs::Request& inRequest, ComputePairs::Response& outResponse) {
        return onComputePairs(inRequest, outResponse);
      });
  service_options.callback_queue = &service_queue_;
  service_ = ioNode.advertiseService(service_options);
  service_spinner_.emplace(1, &service_queue_);
  service_spinner_->start();

  boxes_sub_ = ioNode.subscribe("boxes", static_cast<uint32_t>(params_.boxes_queue_size),
                                &BroadphaseNode::onBoxes, this, ros::TransportHints().tcpNoDelay());
}

BroadphaseNode::~BroadphaseNode() {
  boxes_sub_.shutdown();
  service_spinner_->stop();
  service_.shutdown();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  worker_.join();
}

void BroadphaseNode::onBoxes(const BoxArrayConstPtr& inMsg) {
  if (auto reason = checkBoxArrayShape(*inMsg)) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ++counters_.received;
    }
    refuseFrame(*inMsg, *reason);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.received;
    if (pending_) ++counters_.dropped;  // never started: the newer frame wins
    pending_ = inMsg;
  }
  wake_.notify_one();
}

void BroadphaseNode::workerLoop() {
  for (;;) {
    BoxArrayConstPtr frame;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || pending_; });
      if (stopping_) return;
      frame = std::move(pending_);
      pending_.reset();
    }
    processFrame(*frame);
  }
}

void BroadphaseNode::processFrame(const BoxArray& inMsg) {
  const Clock::time_point start = Clock::now();
  if (auto reason = boxArrayToBoxSet(inMsg, boxes_)) {
    refuseFrame(inMsg, *reason);
    return;
  }
  const double ms_conversion = millisecondsSince(start);

  const PairList& pairs = engine_.update(boxes_);
  const Clock::time_point output_start = Clock::now();
  PairArray pairs_msg;
  pairListToPairArray(pairs, inMsg.header, pairs_msg);
  pairs_pub_.publish(pairs_msg);
  const double ms_message = millisecondsSince(output_start);
  const double ms_total = millisecondsSince(start);

  MarkerCounts marker_counts;
  if (params_.publish_markers && markers_pub_.getNumSubscribers() > 0) {
    visualization_msgs::MarkerArray markers;
    marker_counts = buildMarkers(boxes_, pairs, inMsg.header, params_.markers, markers);
    markers_pub_.publish(markers);
  }

  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.processed;
  }
  FrameStats stats = makeStats(inMsg);
  fillEngineStats(engine_.stats(), stats);
  stats.ms_conversion = ms_conversion;
  stats.ms_output += ms_message;
  stats.ms_total = ms_total;
  stats.marker_boxes = marker_counts.drawn;
  stats.marker_boxes_omitted = marker_counts.colliding_omitted;
  stats_pub_.publish(stats);
}

void BroadphaseNode::refuseFrame(const BoxArray& inMsg, const std::string& inReason) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.refused;
    counters_.last_refusal = inReason;
  }
  ROS_ERROR_THROTTLE(params_.refusal_log_period, "boxes refused (frame '%s', stamp %u.%09u): %s",
                     inMsg.header.frame_id.c_str(), inMsg.header.stamp.sec, inMsg.header.stamp.nsec,
                     inReason.c_str());
  FrameStats stats = makeStats(inMsg);
  stats.path = "refused";
  stats_pub_.publish(stats);
}

FrameStats BroadphaseNode::makeStats(const BoxArray& inMsg) {
  FrameStats stats;
  stats.header = inMsg.header;
  stats.boxes = static_cast<uint32_t>(inMsg.bounds.size() / 6);
  stats.primary_axis = static_cast<uint8_t>(params_.engine.primary_axis);
  stats.secondary_axis = static_cast<uint8_t>(params_.engine.secondary_axis);
  stats.threads = static_cast<uint32_t>(resolveThreadCount(params_.engine.threads));
  std::lock_guard<std::mutex> lock(mutex_);
  stats.frames_received = counters_.received;
  stats.frames_processed = counters_.processed;
  stats.frames_dropped = counters_.dropped;
  stats.frames_refused = counters_.refused;
  stats.last_refusal = counters_.last_refusal;
  return stats;
}

bool BroadphaseNode::onComputePairs(ComputePairs::Request& inRequest,
                                    ComputePairs::Response& outResponse) {
  outResponse.pairs.header = inRequest.boxes.header;
  if (auto reason = boxArrayToBoxSet(inRequest.boxes, service_boxes_)) {
    ROS_ERROR_THROTTLE(params_.refusal_log_period, "compute_pairs refused: %s", reason->c_str());
    outResponse.success = false;
    outResponse.message = *reason;
    return true;  // the call itself succeeded; the answer says why the boxes were refused
  }
  pairListToPairArray(service_engine_.update(service_boxes_), inRequest.boxes.header,
                      outResponse.pairs);
  outResponse.success = true;
  return true;
}

}  // namespace sap_broadphase
