// BroadphaseNode: sources, static world, worker thread, publishers and the compute_pairs service.
#include "sap_broadphase/ros/node.h"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <utility>

#include <dynamic_reconfigure/server.h>
#include <tf2/exceptions.h>
#include <visualization_msgs/MarkerArray.h>
#include <boost/make_shared.hpp>

#include "sap_broadphase/BroadphaseNodeConfig.h"
#include "sap_broadphase/PairEvents.h"
#include "sap_broadphase/ros/conversions.h"
#include "sap_broadphase/ros/markers.h"

namespace sap_broadphase {

namespace {

using Clock = std::chrono::steady_clock;

/// How often the worker wakes without deliveries: source time-outs and /diagnostics.
constexpr double kHousekeepingSeconds = 0.25;

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
  outStats.skin = inEngine.skin;
  outStats.skin_choice = skinChoiceName(inEngine.skin_choice);
  outStats.moved_boxes = static_cast<uint32_t>(inEngine.moved_boxes);
  outStats.max_displacement = inEngine.max_displacement;
  outStats.static_boxes = static_cast<uint32_t>(inEngine.static_boxes);
  outStats.ms_history = inEngine.ms_history;
  outStats.ms_sort = inEngine.ms_keys + inEngine.ms_sort;
  outStats.ms_candidates = inEngine.ms_candidates;
  outStats.ms_pairing = inEngine.ms_pairing;
  outStats.ms_static = inEngine.ms_static;
  outStats.ms_output = inEngine.ms_output;
}

/// Appends the pairs of inFrom that are not in inWithout (both canonical) as consecutive ids.
void appendDifference(const PairList& inFrom, const PairList& inWithout,
                      std::vector<uint32_t>& outIds) {
  PairList difference;
  std::set_difference(inFrom.begin(), inFrom.end(), inWithout.begin(), inWithout.end(),
                      std::back_inserter(difference));
  outIds.reserve(2 * difference.size());
  for (const IdPair& pair : difference) {
    outIds.push_back(pair.a);
    outIds.push_back(pair.b);
  }
}

}  // namespace

BroadphaseNode::BroadphaseNode(ros::NodeHandle& ioNode, const NodeParams& inParams)
    : BroadphaseNode(ioNode, ros::NodeHandle("~"), inParams) {}

BroadphaseNode::BroadphaseNode(ros::NodeHandle& ioNode, const ros::NodeHandle& inPrivate,
                               const NodeParams& inParams)
    : params_(inParams),
      node_(ioNode),
      service_engine_(inParams.engine),
      accepted_(inParams),
      engine_(inParams.engine),
      diagnostics_(ioNode, inPrivate, inPrivate.getNamespace()) {
  ROS_INFO("sap_broadphase: %s", describeNodeParams(params_).c_str());
  pairs_pub_ = ioNode.advertise<PairArray>("pairs", params_.pairs_queue_size);
  events_pub_ = ioNode.advertise<PairEvents>("pair_events", params_.pairs_queue_size);
  stats_pub_ = ioNode.advertise<FrameStats>("stats", 10);
  if (params_.publish_markers)
    markers_pub_ = ioNode.advertise<visualization_msgs::MarkerArray>("markers", 1);
  if (!params_.fixed_frame.empty()) {
    tf_buffer_ = std::make_unique<tf2_ros::Buffer>();
    tf_listener_ = std::make_unique<tf2_ros::TransformListener>(*tf_buffer_, ioNode);
  }
  diagnostics_.setHardwareID("none");
  diagnostics_.add("broadphase", this, &BroadphaseNode::diagnose);

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

  static_sub_ = ioNode.subscribe("static_boxes", 1, &BroadphaseNode::onStaticBoxes, this);
  for (const std::string& topic : params_.sources) {
    ros::SubscribeOptions options;
    options.initByFullCallbackType<const ros::MessageEvent<BoxArray const>&>(
        topic, static_cast<uint32_t>(params_.boxes_queue_size),
        [this, topic](const ros::MessageEvent<BoxArray const>& inEvent) {
          onBoxes(topic, inEvent);
        });
    options.transport_hints = ros::TransportHints().tcpNoDelay();
    source_subs_.push_back(ioNode.subscribe(options));
  }

  // The server starts from whatever the parameter server holds in its own types: a skin of
  // 0.05 or an axis given as 2 would read as the .cfg defaults. The settings in force are
  // given to it before the callback is set, so that the callback's first call (with the
  // server's config) changes nothing.
  reconfigure_ = std::make_unique<dynamic_reconfigure::Server<BroadphaseNodeConfig>>(
      reconfigure_mutex_, inPrivate);
  BroadphaseNodeConfig in_force;
  toReconfigureConfig(params_, in_force);
  reconfigure_->updateConfig(in_force);
  reconfigure_->setCallback([this](BroadphaseNodeConfig& ioConfig, uint32_t inLevel) {
    onReconfigure(ioConfig, inLevel);
  });
}

BroadphaseNode::~BroadphaseNode() {
  reconfigure_.reset();
  for (ros::Subscriber& subscriber : source_subs_) subscriber.shutdown();
  static_sub_.shutdown();
  service_spinner_->stop();
  service_.shutdown();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  worker_.join();
}

void BroadphaseNode::onBoxes(const std::string& inTopic,
                             const ros::MessageEvent<BoxArray const>& inEvent) {
  const BoxArrayConstPtr& msg = inEvent.getConstMessage();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.received;
  }
  const SourceKey key{inTopic, inEvent.getPublisherName()};
  if (auto reason = checkBoxArrayShape(*msg)) {
    refuse(msg->header, msg->bounds.size() / 6, sourceName(key) + ": " + *reason);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    Delivery& slot = pending_[key];
    if (slot.msg) ++counters_.dropped;  // never started: the newer frame of the source wins
    slot = Delivery{msg, ros::Time::now()};
  }
  wake_.notify_one();
}

void BroadphaseNode::onStaticBoxes(const BoxArrayConstPtr& inMsg) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_static_ = inMsg;
  }
  wake_.notify_one();
}

void BroadphaseNode::onReconfigure(BroadphaseNodeConfig& ioConfig, uint32_t /*inLevel*/) {
  NodeParams settings = accepted_;
  const std::string problem = fromReconfigureConfig(ioConfig, settings);
  if (!problem.empty()) {
    ROS_WARN("sap_broadphase: reconfigure refused, the settings in force stay: %s",
             problem.c_str());
    toReconfigureConfig(accepted_, ioConfig);
    return;
  }
  // Written back as the node reads them ("Z" -> "z", "0" -> "off"), so clients see the
  // settings in force.
  toReconfigureConfig(settings, ioConfig);
  const bool new_engine = !sameEngineConfig(settings.engine, accepted_.engine);
  if (!new_engine && sameMarkerSettings(settings, accepted_)) return;
  accepted_ = settings;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_settings_ = settings;
    if (new_engine) pending_service_config_ = settings.engine;
  }
  wake_.notify_one();
}

void BroadphaseNode::applySettings(const NodeParams& inSettings) {
  const bool new_engine = !sameEngineConfig(inSettings.engine, params_.engine);
  if (new_engine) {
    // The engine takes its configuration once, at construction; the new one starts without
    // temporal state (partition bounds, kept candidates, the last frame) and must be told
    // the scenery again.
    engine_ = Broadphase(inSettings.engine);
    if (static_boxes_.size() > 0) engine_.setStaticBoxes(static_boxes_);
  }
  if (inSettings.publish_markers && !markers_pub_)
    markers_pub_ = node_.advertise<visualization_msgs::MarkerArray>("markers", 1);
  else if (!inSettings.publish_markers && markers_pub_)
    markers_pub_.shutdown();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    params_.engine = inSettings.engine;
    params_.publish_markers = inSettings.publish_markers;
    params_.markers = inSettings.markers;
  }
  ROS_INFO("sap_broadphase: reconfigured%s: %s", new_engine ? " (new engine)" : "",
           describeNodeParams(params_).c_str());
}

void BroadphaseNode::workerLoop() {
  const bool fixed_rate = params_.rate > 0.0;
  const auto period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(fixed_rate ? 1.0 / params_.rate : kHousekeepingSeconds));
  Clock::time_point next_tick = Clock::now() + period;
  for (;;) {
    std::map<SourceKey, Delivery> deliveries;
    BoxArrayConstPtr scenery;
    std::optional<NodeParams> settings;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      if (fixed_rate) {
        wake_.wait_until(lock, next_tick, [this] { return stopping_; });
      } else {
        wake_.wait_until(lock, next_tick, [this] {
          return stopping_ || !pending_.empty() || pending_static_ || pending_settings_;
        });
      }
      if (stopping_) return;
      std::swap(deliveries, pending_);
      std::swap(scenery, pending_static_);
      std::swap(settings, pending_settings_);
    }
    // Between two frames, before this batch: every frame delivered after a reconfigure is
    // computed with the new settings.
    if (settings) applySettings(*settings);

    const Clock::time_point now = Clock::now();
    const bool tick = now >= next_tick;
    if (tick) next_tick = std::max(next_tick + period, now);

    bool world_changed = false;
    if (scenery) {
      ingestStatic(*scenery);
      world_changed = true;
    }
    for (auto& [key, delivery] : deliveries) {
      if (!ingest(sourceName(key), *delivery.msg, delivery.msg->header.stamp, converted_)) continue;
      std_msgs::Header header = delivery.msg->header;
      if (tf_buffer_) header.frame_id = params_.fixed_frame;  // the boxes are there now
      sources_.store(key, converted_, header, delivery.received);
      world_changed = true;
      std::lock_guard<std::mutex> lock(mutex_);
      ++counters_.processed;
    }
    if (converted_watch_.shouldShrink(converted_.size(), converted_.ids.capacity()))
      shrinkBoxSet(converted_);
    expireSources();
    if (sources_.size() > 0 && (fixed_rate ? tick : world_changed)) computeFrame();
    diagnostics_.update();
  }
}

bool BroadphaseNode::ingest(const std::string& inWhat, const BoxArray& inMsg,
                            const ros::Time& inWhen, BoxSet& outBoxes) {
  if (auto reason = boxArrayToBoxSet(inMsg, outBoxes)) {
    refuse(inMsg.header, inMsg.bounds.size() / 6, inWhat + ": " + *reason);
    return false;
  }
  if (!tf_buffer_) return true;
  std::string error;
  if (!tf_buffer_->canTransform(params_.fixed_frame, inMsg.header.frame_id, inWhen,
                                ros::Duration(params_.transform_timeout), &error)) {
    skip(inWhat, error);
    return false;
  }
  try {
    const geometry_msgs::TransformStamped transform =
        tf_buffer_->lookupTransform(params_.fixed_frame, inMsg.header.frame_id, inMsg.header.stamp);
    transformBoxes(transform.transform, outBoxes);
  } catch (const tf2::TransformException& exception) {
    skip(inWhat, exception.what());
    return false;
  }
  return true;
}

void BroadphaseNode::ingestStatic(const BoxArray& inMsg) {
  BoxSet scenery;
  // Scenery stays put, and a latched message may be older than tf2's cache: its frame is
  // placed with the latest transform (time 0), not the one at its stamp.
  if (!ingest(kStaticSourceName, inMsg, ros::Time(0), scenery)) return;
  static_ids_ = scenery.ids;
  std::sort(static_ids_.begin(), static_ids_.end());
  static_ids_.shrink_to_fit();
  static_frame_ = tf_buffer_ ? params_.fixed_frame : inMsg.header.frame_id;
  if (scenery.size() == 0) static_frame_.clear();  // no scenery: no frame to agree with
  engine_.setStaticBoxes(scenery);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    counters_.static_boxes = static_cast<uint32_t>(scenery.size());
  }
  ROS_INFO("sap_broadphase: static_boxes: %zu boxes indexed (frame '%s')", scenery.size(),
           inMsg.header.frame_id.c_str());
  static_boxes_ = std::move(scenery);
}

void BroadphaseNode::expireSources() {
  for (const std::string& name : sources_.expire(ros::Time::now(), params_.source_timeout)) {
    const std::string message = name + " silent for more than ~source_timeout (" +
                                std::to_string(params_.source_timeout) + " s): dropped out";
    ROS_WARN("sap_broadphase: %s", message.c_str());
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.timed_out;
    counters_.last_error = message;
  }
}

void BroadphaseNode::computeFrame() {
  const Clock::time_point start = Clock::now();
  WorldAssembly assembly;
  const BoxSet& world = sources_.assemble(
      static_ids_, tf_buffer_ ? params_.fixed_frame : static_frame_, world_, assembly);
  if (tf_buffer_) assembly.header.frame_id = params_.fixed_frame;
  for (const std::string& refusal : assembly.refusals)
    refuse(assembly.header, world.size(), refusal);
  if (world_watch_.shouldShrink(world_.size(), world_.ids.capacity())) shrinkBoxSet(world_);
  if (assembly.sources_merged == 0) return;
  const double ms_conversion = millisecondsSince(start);

  const PairList& pairs = engine_.update(world);
  const Clock::time_point output_start = Clock::now();
  auto pairs_msg = boost::make_shared<PairArray>();
  pairListToPairArray(pairs, assembly.header, *pairs_msg);
  pairs_pub_.publish(pairs_msg);
  const double ms_message = millisecondsSince(output_start);
  const double ms_total = millisecondsSince(start);
  publishEvents(pairs, assembly.header);

  MarkerCounts marker_counts;
  if (params_.publish_markers && markers_pub_.getNumSubscribers() > 0) {
    auto markers = boost::make_shared<visualization_msgs::MarkerArray>();
    marker_counts = buildMarkers(world, pairs, assembly.header, params_.markers, *markers);
    markers_pub_.publish(markers);
  }

  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.computed;
    counters_.live_sources = static_cast<uint32_t>(assembly.sources_merged);
    counters_.last_ms_total = ms_total;
    counters_.max_ms_total = std::max(counters_.max_ms_total, ms_total);
  }
  auto stats = boost::make_shared<FrameStats>(makeStats(assembly.header, world.size()));
  fillEngineStats(engine_.stats(), *stats);
  stats->ms_conversion = ms_conversion;
  stats->ms_output += ms_message;
  stats->ms_total = ms_total;
  stats->marker_boxes = marker_counts.drawn;
  stats->marker_boxes_omitted = marker_counts.colliding_omitted;
  stats_pub_.publish(stats);
}

void BroadphaseNode::publishEvents(const PairList& inPairs, const std_msgs::Header& inHeader) {
  if (events_pub_.getNumSubscribers() == 0) {
    // Nobody listens: no copy of the pairs is kept; the next listener's first message reports
    // every pair of its first frame as began.
    previous_pairs_valid_ = false;
    PairList().swap(previous_pairs_);
    return;
  }
  auto events = boost::make_shared<PairEvents>();
  events->header = inHeader;
  static const PairList kNone;
  const PairList& previous = previous_pairs_valid_ ? previous_pairs_ : kNone;
  appendDifference(inPairs, previous, events->began);
  appendDifference(previous, inPairs, events->ended);
  events_pub_.publish(events);
  previous_pairs_.assign(inPairs.begin(), inPairs.end());
  previous_pairs_valid_ = true;
}

void BroadphaseNode::refuse(const std_msgs::Header& inHeader, std::size_t inBoxes,
                            const std::string& inReason) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.refused;
    counters_.last_refusal = inReason;
    counters_.last_error = inReason;
  }
  ROS_ERROR_THROTTLE(params_.refusal_log_period, "boxes refused (frame '%s', stamp %u.%09u): %s",
                     inHeader.frame_id.c_str(), inHeader.stamp.sec, inHeader.stamp.nsec,
                     inReason.c_str());
  auto stats = boost::make_shared<FrameStats>(makeStats(inHeader, inBoxes));
  stats->path = "refused";
  stats_pub_.publish(stats);
}

void BroadphaseNode::skip(const std::string& inWhat, const std::string& inReason) {
  const std::string message = inWhat + " skipped: no transform into '" + params_.fixed_frame +
                              "' within ~transform_timeout: " + inReason;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.skipped;
    counters_.last_error = message;
  }
  ROS_WARN_THROTTLE(params_.refusal_log_period, "sap_broadphase: %s", message.c_str());
}

FrameStats BroadphaseNode::makeStats(const std_msgs::Header& inHeader, std::size_t inBoxes) {
  FrameStats stats;
  stats.header = inHeader;
  stats.boxes = static_cast<uint32_t>(inBoxes);
  std::lock_guard<std::mutex> lock(mutex_);  // refusals come from any thread
  stats.primary_axis = static_cast<uint8_t>(params_.engine.primary_axis);
  stats.secondary_axis = static_cast<uint8_t>(params_.engine.secondary_axis);
  stats.threads = static_cast<uint32_t>(resolveThreadCount(params_.engine.threads));
  stats.static_world_boxes = counters_.static_boxes;
  stats.frames_received = counters_.received;
  stats.frames_processed = counters_.processed;
  stats.frames_dropped = counters_.dropped;
  stats.frames_refused = counters_.refused;
  stats.frames_skipped = counters_.skipped;
  stats.frames_computed = counters_.computed;
  stats.sources = counters_.live_sources;
  stats.sources_timed_out = counters_.timed_out;
  stats.last_refusal = counters_.last_refusal;
  return stats;
}

void BroadphaseNode::diagnose(diagnostic_updater::DiagnosticStatusWrapper& ioStatus) {
  std::lock_guard<std::mutex> lock(mutex_);
  const ros::WallTime now = ros::WallTime::now();
  const double seconds = reported_at_.isZero() ? 0.0 : (now - reported_at_).toSec();
  const uint64_t new_refusals = counters_.refused - reported_.refused;
  const uint64_t new_skips = counters_.skipped - reported_.skipped;
  const uint64_t new_time_outs = counters_.timed_out - reported_.timed_out;
  if (new_refusals + new_skips + new_time_outs > 0)
    ioStatus.summary(diagnostic_msgs::DiagnosticStatus::WARN, counters_.last_error);
  else if (counters_.computed == 0)
    ioStatus.summary(diagnostic_msgs::DiagnosticStatus::OK, "waiting for boxes");
  else
    ioStatus.summary(diagnostic_msgs::DiagnosticStatus::OK, "computing");
  ioStatus.add("frame rate (Hz)",
               seconds > 0.0 ? (counters_.computed - reported_.computed) / seconds : 0.0);
  ioStatus.add("last latency (ms)", counters_.last_ms_total);
  ioStatus.add("max latency since last report (ms)", counters_.max_ms_total);
  ioStatus.add("live sources", counters_.live_sources);
  ioStatus.add("static boxes", counters_.static_boxes);
  ioStatus.add("frames computed", counters_.computed);
  ioStatus.add("source frames received", counters_.received);
  ioStatus.add("source frames dropped", counters_.dropped);
  ioStatus.add("refusals", counters_.refused);
  ioStatus.add("frames skipped (no transform)", counters_.skipped);
  ioStatus.add("sources timed out", counters_.timed_out);
  ioStatus.add("last error", counters_.last_error);
  reported_ = counters_;
  reported_at_ = now;
  counters_.max_ms_total = 0.0;
}

bool BroadphaseNode::onComputePairs(ComputePairs::Request& inRequest,
                                    ComputePairs::Response& outResponse) {
  std::optional<BroadphaseConfig> config;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    std::swap(config, pending_service_config_);
  }
  if (config) service_engine_ = Broadphase(*config);
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
  if (service_watch_.shouldShrink(service_boxes_.size(), service_boxes_.ids.capacity()))
    shrinkBoxSet(service_boxes_);
  return true;
}

}  // namespace sap_broadphase
