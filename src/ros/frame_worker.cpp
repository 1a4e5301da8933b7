// FrameWorker: the worker thread, its engine and the world of a frame.
#include "frame_worker.h"

#include <algorithm>
#include <chrono>
#include <utility>

#include "checked_callbacks.h"
#include "sap_broadphase/ros/conversions.h"

namespace sap_broadphase {

namespace {

/// How often (in ROS time) the worker wakes without deliveries: source time-outs, frames
/// waiting for tf, /diagnostics.
constexpr double kHousekeepingSeconds = 0.25;
/// Under use_sim_time ROS time moves with /clock, which wakes no condition variable: the
/// worker looks at the clock again after at most this many wall seconds.
constexpr double kSimTimePollSeconds = 0.005;

double millisecondsSince(std::chrono::steady_clock::time_point inStart) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - inStart)
      .count();
}

}  // namespace

FrameWorker::FrameWorker(const NodeParams& inParams, SourceIngest& ioIngest,
                         FrameOutputs& ioOutputs, NodeStatus& ioStatus)
    : params_(inParams),
      ingest_(ioIngest),
      outputs_(ioOutputs),
      status_(ioStatus),
      engine_(inParams.engine),
      thread_(&FrameWorker::run, this) {}

FrameWorker::~FrameWorker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void FrameWorker::wake() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    woken_ = true;
  }
  wake_.notify_one();
}

void FrameWorker::reconfigure(const NodeParams& inSettings) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_settings_ = inSettings;
    woken_ = true;
  }
  wake_.notify_one();
}

QueryHitList FrameWorker::query(const BoxSet& inQueries) const {
  std::shared_lock<std::shared_mutex> lock(engine_mutex_);
  return engine_.query(inQueries);
}

bool FrameWorker::waitUntil(const ros::Time& inDeadline, const ros::Duration& inPeriod) {
  // With a fixed ~rate, deliveries wait for the tick; only settings and stopping do not.
  const bool fixed_rate = params_.rate > 0.0;
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    if (stopping_) return false;
    if (woken_ && (!fixed_rate || pending_settings_)) break;
    const ros::Time now = ros::Time::now();
    // Past the deadline, or the clock went back (the deadline is more than a period ahead).
    if (now >= inDeadline || now + inPeriod < inDeadline) break;
    double seconds = (inDeadline - now).toSec();
    if (ros::Time::isSimTime()) seconds = std::min(seconds, kSimTimePollSeconds);
    wake_.wait_for(lock, std::chrono::duration<double>(seconds));
  }
  if (!fixed_rate || pending_settings_) woken_ = false;
  return true;
}

void FrameWorker::run() {
  const bool fixed_rate = params_.rate > 0.0;
  const ros::Duration period(fixed_rate ? 1.0 / params_.rate : kHousekeepingSeconds);
  ros::Time next_tick = ros::Time::now() + period;
  for (;;) {
    if (!waitUntil(next_tick, period)) return;
    std::optional<NodeParams> settings;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      std::swap(settings, pending_settings_);
    }
    // Between two frames, before this batch: every frame delivered after a reconfigure is
    // computed with the new settings.
    if (settings) applySettings(*settings);

    const ros::Time now = ros::Time::now();
    if (now < last_now_) restartClock(now);
    last_now_ = now;
    if (now + period < next_tick) next_tick = now + period;  // the clock went back (a bag loop)
    const bool tick = now >= next_tick;
    // Ticks keep their phase; one that is more than a period late (a slow frame, /clock
    // jumping ahead) is not made up for: the next one is a period from now.
    if (tick) {
      next_tick += period;
      if (next_tick <= now) next_tick = now + period;
    }
    if (fixed_rate && !tick) continue;  // woken for settings only

    runGuarded(
        [&] {
          const bool scenery_changed = takeScenery();
          const bool sources_changed = takeDeliveries();
          expireSources();
          // Before the frame: its boxes were named when their messages were converted, so
          // id_names reaches listeners before the pairs that use the names, and the frame's
          // markers label its new boxes.
          ingest_.publishIdNames();
          if (sources_.size() > 0 && (fixed_rate ? tick : scenery_changed || sources_changed))
            computeFrame();
          ingest_.countLostMessages();
          status_.updateDiagnostics();
        },
        [&](const std::string& inWhat) { recoverFrom(inWhat); });
  }
}

void FrameWorker::restartClock(const ros::Time& inNow) {
  // As tf2 and rosbag users expect of ROS 1 ("detected jump back in time"): the times kept
  // from the old clock mean nothing on the new one.
  ROS_WARN(
      "sap_broadphase: detected jump back in time of %.3f s: receipt times and time-outs "
      "of %zu sources start again",
      (last_now_ - inNow).toSec(), sources_.size());
  sources_.restartClock(inNow);
  ingest_.restartClock(inNow);
  status_.restartClock();
}

void FrameWorker::recoverFrom(const std::string& inWhat) {
  // An exception (std::bad_alloc of a frame too large for the memory left) may have left the
  // engine's temporal state half updated: the next frame starts on a new engine.
  status_.refuse(std_msgs::Header(), 0,
                 "a frame could not be computed (" + inWhat + "): refused, new engine");
  std::lock_guard<std::shared_mutex> lock(engine_mutex_);
  engine_ = Broadphase(params_.engine);
  if (static_boxes_.size() > 0) engine_.setStaticBoxes(static_boxes_);
}

void FrameWorker::applySettings(const NodeParams& inSettings) {
  const bool new_engine = !sameConfig(inSettings.engine, params_.engine);
  if (new_engine) {
    // The engine takes its configuration once, at construction; the new one starts without
    // temporal state (partition bounds, kept candidates, the last frame) and must be told
    // the scenery again.
    std::lock_guard<std::shared_mutex> lock(engine_mutex_);
    engine_ = Broadphase(inSettings.engine);
    if (static_boxes_.size() > 0) engine_.setStaticBoxes(static_boxes_);
    status_.setEngineConfig(inSettings.engine);
  }
  outputs_.setMarkers(inSettings.publish_markers, inSettings.markers);
  params_.engine = inSettings.engine;
  params_.publish_markers = inSettings.publish_markers;
  params_.markers = inSettings.markers;
  ROS_INFO("sap_broadphase: reconfigured%s: %s", new_engine ? " (new engine)" : "",
           describeNodeParams(params_).c_str());
}

bool FrameWorker::takeScenery() {
  BoxArrayConstPtr scenery_msg;
  ingest_.take(deliveries_, scenery_msg);
  if (!scenery_msg) return false;
  BoxSet scenery;
  if (!ingest_.convertScenery(*scenery_msg, scenery)) return false;
  static_ids_ = scenery.ids;
  std::sort(static_ids_.begin(), static_ids_.end());
  static_ids_.shrink_to_fit();
  static_frame_ =
      ingest_.fixedFrame().empty() ? scenery_msg->header.frame_id : ingest_.fixedFrame();
  if (scenery.size() == 0) static_frame_.clear();  // no scenery: no frame to agree with
  {
    std::lock_guard<std::shared_mutex> lock(engine_mutex_);
    engine_.setStaticBoxes(scenery);
  }
  status_.setStaticBoxes(scenery.size());
  ROS_INFO("sap_broadphase: static_boxes: %zu boxes indexed (frame '%s')", scenery.size(),
           scenery_msg->header.frame_id.c_str());
  static_boxes_ = std::move(scenery);
  return true;
}

bool FrameWorker::takeDeliveries() {
  bool changed = false;
  for (auto& [key, delivery] : deliveries_) {
    if (ingest_.fixedFrame().empty()) {
      // No transform to apply: the frame is kept as published, checked where it is read.
      sources_.storeMessage(key, delivery.msg, delivery.received);
      changed = true;
      continue;
    }
    if (!ingest_.convert(key, *delivery.msg, converted_)) continue;
    std_msgs::Header header = delivery.msg->header;
    header.frame_id = ingest_.fixedFrame();  // moved there
    sources_.store(key, converted_, header, delivery.received);
    status_.countProcessed();
    changed = true;
  }
  deliveries_.clear();
  if (converted_watch_.shouldGiveBack(converted_.size(), converted_.ids.capacity()))
    shrinkBoxSet(converted_);
  return changed;
}

void FrameWorker::expireSources() {
  // A ~sources entry's own timeout, else ~source_timeout.
  const auto timeout_of = [this](const SourceKey& inKey) {
    for (const SourceSpec& spec : params_.sources)
      if (spec.topic == inKey.topic && spec.timeout) return *spec.timeout;
    return params_.source_timeout;
  };
  const std::vector<SourceSet::Expired> expired = sources_.expire(ros::Time::now(), timeout_of);
  if (!expired.empty() && sources_.size() == 0) {
    // No frame follows until a source comes back: the last one must not stay in the world.
    std::lock_guard<std::shared_mutex> lock(engine_mutex_);
    engine_.update(BoxSet());
  }
  for (const auto& [key, frames] : expired) {
    ingest_.forget(key);
    const bool own = timeout_of(key) != params_.source_timeout;
    const std::string timeout =
        (own ? "the timeout of its ~sources entry (" : "~source_timeout (") +
        std::to_string(timeout_of(key)) + " s)";
    if (frames == 1) {
      // One frame, then silence (rostopic pub -1, a one-shot tool): as published, not a
      // stream that broke off.
      status_.timeOut(sourceName(key) + " published one frame, older now than " + timeout +
                          ": dropped out (~source_timeout 0 keeps such a source)",
                      false);
    } else {
      status_.timeOut(sourceName(key) + " silent for more than " + timeout + ": dropped out", true);
    }
  }
}

void FrameWorker::computeFrame() {
  const auto start = std::chrono::steady_clock::now();
  const std::string& fixed_frame = ingest_.fixedFrame();
  WorldAssembly assembly;
  const World world =
      sources_.assemble(static_ids_, fixed_frame.empty() ? static_frame_ : fixed_frame, world_,
                        assembly, outputs_.wantsMarkers());
  if (!fixed_frame.empty()) assembly.header.frame_id = fixed_frame;
  for (const auto* refused_list : {&assembly.refused_frames, &assembly.refusals})
    for (const RefusedFrame& refused : *refused_list)
      status_.refuse(refused.header, refused.boxes, refused.reason);
  for (std::size_t i = 0; i < assembly.frames_accepted; ++i) status_.countProcessed();
  if (world_watch_.shouldGiveBack(world_.size(), world_.ids.capacity())) shrinkBoxSet(world_);
  if (assembly.sources_merged == 0) return;

  FrameAccount frame;
  frame.header = assembly.header;
  frame.boxes = world.size();
  frame.sources = assembly.sources_merged;
  frame.ms_conversion = millisecondsSince(start);
  const PairList* pairs = updateEngine(world);
  if (!pairs) return;
  frame.ms_message = outputs_.publishPairs(*pairs, assembly.header);
  frame.ms_total = millisecondsSince(start);
  outputs_.publishEvents(*pairs, assembly.header);
  if (world.boxes) {  // markers are drawn from boxes; a world that is one message has none
    const MarkerCounts markers =
        outputs_.publishMarkers(*world.boxes, *pairs, assembly.header, ingest_.idNames());
    frame.marker_boxes = markers.drawn;
    frame.marker_boxes_omitted = markers.colliding_omitted;
  }
  status_.frameComputed(frame, engine_.stats());
}

const PairList* FrameWorker::updateEngine(const World& inWorld) {
  try {
    std::unique_lock<std::shared_mutex> lock(engine_mutex_);
    const PairList& pairs = engine_.update(
        inWorld.boxes ? BoxFrame(*inWorld.boxes) : BoxFrame(boxArrayRecords(*inWorld.message)));
    lock.unlock();
    if (inWorld.message && sources_.accept(inWorld.source)) status_.countProcessed();
    return &pairs;
  } catch (const InvalidBoxes& refusal) {
    // As a frame refused at conversion: counted and named, nothing published, and the source
    // keeps its last good frame. A merged world was checked source by source as it was built.
    const std_msgs::Header header = inWorld.message ? inWorld.message->header : std_msgs::Header();
    status_.refuse(header, inWorld.size(),
                   sourceName(inWorld.source) + ": " + refusal.error().message());
    if (inWorld.message) sources_.refuse(inWorld.source);
    return nullptr;
  }
}

}  // namespace sap_broadphase
