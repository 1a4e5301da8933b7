// NodeStatus: counters, `stats` and /diagnostics.
#include "node_status.h"

#include <algorithm>

#include <boost/make_shared.hpp>

namespace sap_broadphase {

namespace {

/// Copies the engine's account of a frame into the stats message.
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
  outStats.skin = inEngine.skin;
  outStats.skin_choice = skinChoiceName(inEngine.skin_choice);
  outStats.moved_boxes = static_cast<uint32_t>(inEngine.moved_boxes);
  outStats.max_displacement = inEngine.max_displacement;
  outStats.static_boxes = static_cast<uint32_t>(inEngine.static_boxes);
  // FrameStats keeps its fields: the engine's own flow (ms_plan) counts with the history, and
  // skin reuse (growing, keeping, the kept candidates' pass) with pairing, as the message says.
  outStats.ms_history = inEngine.ms_history + inEngine.ms_plan;
  outStats.ms_sort = inEngine.ms_keys + inEngine.ms_sort;
  outStats.ms_candidates = inEngine.ms_candidates;
  outStats.ms_pairing = inEngine.ms_pairing + inEngine.ms_skin;
  outStats.ms_static = inEngine.ms_static;
  outStats.ms_output = inEngine.ms_output;
}

}  // namespace

NodeStatus::NodeStatus(ros::NodeHandle& ioNode, const ros::NodeHandle& inPrivate,
                       const BroadphaseConfig& inEngine, int inLogPeriod)
    : stats_pub_(ioNode.advertise<FrameStats>("stats", 10)),
      log_period_(inLogPeriod),
      engine_(inEngine),
      diagnostics_(ioNode, inPrivate, inPrivate.getNamespace()) {
  diagnostics_.setHardwareID("none");
  diagnostics_.add("broadphase", this, &NodeStatus::diagnose);
}

void NodeStatus::countReceived() {
  std::lock_guard<std::mutex> lock(mutex_);
  ++counters_.received;
}

void NodeStatus::countDropped() {
  std::lock_guard<std::mutex> lock(mutex_);
  ++counters_.dropped;
}

void NodeStatus::countProcessed() {
  std::lock_guard<std::mutex> lock(mutex_);
  ++counters_.processed;
}

void NodeStatus::setStaticBoxes(std::size_t inBoxes) {
  std::lock_guard<std::mutex> lock(mutex_);
  counters_.static_boxes = static_cast<uint32_t>(inBoxes);
}

void NodeStatus::setEngineConfig(const BroadphaseConfig& inEngine) {
  std::lock_guard<std::mutex> lock(mutex_);
  engine_ = inEngine;
}

void NodeStatus::refuse(const std_msgs::Header& inHeader, std::size_t inBoxes,
                        const std::string& inReason) {
  boost::shared_ptr<FrameStats> stats;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.refused;
    counters_.last_refusal = inReason;
    counters_.last_error = inReason;
    stats = boost::make_shared<FrameStats>(makeStats(inHeader, inBoxes));
  }
  ROS_ERROR_THROTTLE(log_period_, "boxes refused (frame '%s', stamp %u.%09u): %s",
                     inHeader.frame_id.c_str(), inHeader.stamp.sec, inHeader.stamp.nsec,
                     inReason.c_str());
  stats->path = "refused";
  stats_pub_.publish(stats);
}

void NodeStatus::skip(const std::string& inMessage) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.skipped;
    counters_.last_error = inMessage;
  }
  ROS_WARN_THROTTLE(log_period_, "sap_broadphase: %s", inMessage.c_str());
}

void NodeStatus::lose(uint64_t inCount, const std::string& inTopic) {
  const std::string message =
      "'" + inTopic + "': " + std::to_string(inCount) +
      " MarkerArray messages lost in the subscriber queue (a burst faster than the node reads): "
      "the marker set misses their changes until the publisher sends them again";
  {
    std::lock_guard<std::mutex> lock(mutex_);
    counters_.lost += inCount;
    counters_.last_error = message;
  }
  ROS_WARN_THROTTLE(log_period_, "sap_broadphase: %s", message.c_str());
}

void NodeStatus::setRefusedPublishers(const std::vector<std::string>& inNames) {
  std::string names;
  for (const std::string& name : inNames) names += (names.empty() ? "" : ", ") + name;
  std::lock_guard<std::mutex> lock(mutex_);
  counters_.refused_publishers = names;
}

void NodeStatus::timeOut(const std::string& inMessage, bool inUnexpected) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.timed_out;
    if (inUnexpected) counters_.last_error = inMessage;
  }
  if (inUnexpected)
    ROS_WARN("sap_broadphase: %s", inMessage.c_str());
  else
    ROS_INFO("sap_broadphase: %s", inMessage.c_str());
}

void NodeStatus::restartClock() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    reported_at_ = ros::Time();
  }
  // The updater waits for a time of the old clock: it reports now and counts from now.
  diagnostics_.force_update();
}

void NodeStatus::setLiveSources(std::size_t inLive, std::size_t inConfigured) {
  std::lock_guard<std::mutex> lock(mutex_);
  counters_.held_sources = static_cast<uint32_t>(inLive);
  counters_.configured_sources = static_cast<uint32_t>(inConfigured);
}

void NodeStatus::frameComputed(const FrameAccount& inFrame, const FrameReport& inEngine) {
  auto stats = boost::make_shared<FrameStats>();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.computed;
    counters_.live_sources = static_cast<uint32_t>(inFrame.sources);
    counters_.last_ms_total = inFrame.ms_total;
    counters_.max_ms_total = std::max(counters_.max_ms_total, inFrame.ms_total);
    *stats = makeStats(inFrame.header, inFrame.boxes);
  }
  fillEngineStats(inEngine, *stats);
  stats->ms_conversion = inFrame.ms_conversion;
  stats->ms_output += inFrame.ms_message;
  stats->ms_total = inFrame.ms_total;
  stats->marker_boxes = inFrame.marker_boxes;
  stats->marker_boxes_omitted = inFrame.marker_boxes_omitted;
  stats_pub_.publish(stats);
}

FrameStats NodeStatus::makeStats(const std_msgs::Header& inHeader, std::size_t inBoxes) const {
  FrameStats stats;
  stats.header = inHeader;
  stats.boxes = static_cast<uint32_t>(inBoxes);
  stats.primary_axis = static_cast<uint8_t>(engine_.primary_axis);
  stats.secondary_axis = static_cast<uint8_t>(engine_.secondary_axis);
  stats.threads = static_cast<uint32_t>(resolveThreadCount(engine_.threads));
  stats.static_world_boxes = counters_.static_boxes;
  stats.frames_received = counters_.received;
  stats.frames_processed = counters_.processed;
  stats.frames_dropped = counters_.dropped;
  stats.frames_refused = counters_.refused;
  stats.frames_skipped = counters_.skipped;
  stats.frames_computed = counters_.computed;
  stats.sources = counters_.live_sources;
  stats.sources_timed_out = counters_.timed_out;
  stats.messages_lost = counters_.lost;
  stats.last_refusal = counters_.last_refusal;
  return stats;
}

void NodeStatus::summarize(diagnostic_updater::DiagnosticStatusWrapper& ioStatus) const {
  using diagnostic_msgs::DiagnosticStatus;
  const std::string configured = std::to_string(counters_.configured_sources) + " in ~sources";
  if (counters_.held_sources == 0 && counters_.computed == 0) {
    ioStatus.summary(DiagnosticStatus::OK,
                     "waiting for boxes: no source of the " + configured + " has published yet");
  } else if (counters_.held_sources == 0) {
    // Every source went silent past its time-out: the node computes nothing until one returns.
    std::string text = "computing nothing: no live source of the " + configured;
    if (!counters_.last_error.empty()) text += " (last error: " + counters_.last_error + ")";
    ioStatus.summary(DiagnosticStatus::WARN, text);
  } else if (counters_.computed == reported_.computed) {
    ioStatus.summary(DiagnosticStatus::OK, "no new frame since the last report: " +
                                               std::to_string(counters_.held_sources) +
                                               " live sources hold their last frames");
  } else {
    ioStatus.summary(DiagnosticStatus::OK, "computing");
  }
}

void NodeStatus::diagnose(diagnostic_updater::DiagnosticStatusWrapper& ioStatus) {
  std::lock_guard<std::mutex> lock(mutex_);
  const ros::Time now = ros::Time::now();
  const double seconds = reported_at_.isZero() ? 0.0 : (now - reported_at_).toSec();
  const uint64_t new_refusals = counters_.refused - reported_.refused;
  const uint64_t new_skips = counters_.skipped - reported_.skipped;
  const uint64_t new_time_outs = counters_.timed_out - reported_.timed_out;
  const uint64_t new_losses = counters_.lost - reported_.lost;
  if (new_refusals + new_skips + new_time_outs + new_losses > 0)
    ioStatus.summary(diagnostic_msgs::DiagnosticStatus::WARN, counters_.last_error);
  else
    summarize(ioStatus);
  ioStatus.add("frame rate (Hz)",
               seconds > 0.0 ? (counters_.computed - reported_.computed) / seconds : 0.0);
  ioStatus.add("last latency (ms)", counters_.last_ms_total);
  ioStatus.add("max latency since last report (ms)", counters_.max_ms_total);
  ioStatus.add("live sources", counters_.held_sources);
  ioStatus.add("configured sources", counters_.configured_sources);
  ioStatus.add("static boxes", counters_.static_boxes);
  ioStatus.add("frames computed", counters_.computed);
  ioStatus.add("source frames received", counters_.received);
  ioStatus.add("source frames dropped", counters_.dropped);
  ioStatus.add("refusals", counters_.refused);
  ioStatus.add("frames skipped (no transform)", counters_.skipped);
  ioStatus.add("sources timed out", counters_.timed_out);
  ioStatus.add("MarkerArray messages lost", counters_.lost);
  ioStatus.add("refused publishers", counters_.refused_publishers);
  ioStatus.add("last error", counters_.last_error);
  reported_ = counters_;
  reported_at_ = now;
  counters_.max_ms_total = 0.0;
}

}  // namespace sap_broadphase
