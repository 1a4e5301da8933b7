// FrameWorker: the worker thread, its engine and the world of a frame.
#include "frame_worker.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <utility>

#include "checked_callbacks.h"

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
      scenery_index_(std::make_shared<SceneryIndex>(nullptr, inParams.engine)),
      thread_() {
  publishWorld(sceneryHeader(), {});
  thread_ = std::thread(&FrameWorker::run, this);
}

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

QueryAnswer FrameWorker::query(const BoxFrame& inQueries) const {
  std::shared_ptr<const WorldSnapshot> world;
  {
    std::lock_guard<std::mutex> lock(snapshot_mutex_);
    world = snapshot_;
  }
  QueryAnswer answer;
  answer.hits = world->query(inQueries);
  answer.header = world->header();
  return answer;
}

void FrameWorker::publishWorld(const std_msgs::Header& inHeader,
                               std::vector<SourceFramePtr> inFrames) {
  snapshot_header_ = inHeader;
  snapshot_frames_ = std::move(inFrames);
  auto world = std::make_shared<const WorldSnapshot>(snapshot_header_, snapshot_frames_,
                                                     scenery_index_, params_.engine);
  // While queries keep coming (the snapshot it replaces was read), the worker indexes the
  // frame before publishing it, so that queries only read: otherwise the frame's first query
  // builds the index on its thread, competing with the worker for the cores, and the frame's
  // other queries wait for it.
  if (queriesComing()) world->index();
  std::lock_guard<std::mutex> lock(snapshot_mutex_);
  snapshot_ = std::move(world);  // the one it replaces goes with its last query
}

bool FrameWorker::queriesComing() const {
  std::lock_guard<std::mutex> lock(snapshot_mutex_);
  return snapshot_ && snapshot_->asked();
}

void FrameWorker::publishScenery() {
  scenery_index_ = std::make_shared<const SceneryIndex>(scenery_, params_.engine);
  publishWorld(snapshot_header_, snapshot_frames_);
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
          status_.setLiveSources(sources_.size(), params_.sources.size());
          // Before the frame: its boxes were named when their messages were converted, so
          // id_names reaches listeners before the pairs that use the names, and the frame's
          // markers label its new boxes.
          ingest_.upkeep().publishIdNames();
          if (sources_.size() > 0 && (fixed_rate ? tick : scenery_changed || sources_changed))
            computeFrame();
          ingest_.upkeep().countLostMessages();
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
  ingest_.mailbox().restartClock(inNow);
  status_.restartClock();
}

void FrameWorker::recoverFrom(const std::string& inWhat) {
  // An exception (std::bad_alloc of a frame too large for the memory left) may have left the
  // engine's temporal state half updated: the next frame starts on a new engine.
  status_.refuse(std_msgs::Header(), 0,
                 "a frame could not be computed (" + inWhat + "): refused, new engine");
  outputs_.restartEvents();  // the last published pairs may have gone with the failure
  engine_ = Broadphase(params_.engine);
  if (scenery_) engine_.setStaticBoxes(scenery_->span());
  snapshot_frames_.clear();  // the new engine's world is the scenery alone
  snapshot_header_ = sceneryHeader();
  publishScenery();
}

std_msgs::Header FrameWorker::sceneryHeader() const {
  std_msgs::Header header;
  header.frame_id =
      ingest_.placement().fixedFrame().empty() ? static_frame_ : ingest_.placement().fixedFrame();
  return header;
}

void FrameWorker::applySettings(const NodeParams& inSettings) {
  const bool new_engine = !sameConfig(inSettings.engine, params_.engine);
  if (new_engine) {
    // The engine takes its configuration once, at construction; the new one starts without
    // temporal state (partition bounds, kept candidates, the last frame) and must be told
    // the scenery again.
    outputs_.holdLastPairs();  // pair_events still tells what changed since the last frame
    engine_ = Broadphase(inSettings.engine);
    if (scenery_) engine_.setStaticBoxes(scenery_->span());
    status_.setEngineConfig(inSettings.engine);
  }
  outputs_.setMarkers(inSettings.publish_markers, inSettings.markers);
  params_.engine = inSettings.engine;
  if (new_engine) {
    snapshot_frames_.clear();  // the new engine's world is the scenery alone
    snapshot_header_ = sceneryHeader();
    publishScenery();  // indexed with the new settings
  }
  params_.publish_markers = inSettings.publish_markers;
  params_.markers = inSettings.markers;
  ROS_INFO("sap_broadphase: reconfigured%s: %s", new_engine ? " (new engine)" : "",
           describeNodeParams(params_).c_str());
}

bool FrameWorker::takeScenery() {
  BoxArrayConstPtr message;
  ingest_.mailbox().take(deliveries_, message);
  if (!message) return false;
  auto scenery = std::make_shared<SourceFrame>();
  scenery->header = message->header;
  scenery->message = message;
  // An empty scenery (clearing it) needs no transform.
  if (scenery->size() > 0 && !place(kStaticSourceName, ros::Time(0), *scenery)) return false;
  try {
    engine_.setStaticBoxes(scenery->span());
  } catch (const InvalidBoxes& refusal) {  // the scenery in force stays
    status_.refuse(message->header, scenery->size(),
                   std::string(kStaticSourceName) + ": " + refusal.error().message());
    return false;
  }
  static_frame_ = ingest_.placement().fixedFrame().empty() ? message->header.frame_id
                                                           : ingest_.placement().fixedFrame();
  if (scenery->size() == 0) static_frame_.clear();  // no scenery: no frame to agree with
  status_.setStaticBoxes(scenery->size());
  ROS_INFO("sap_broadphase: static_boxes: %zu %s indexed (frame '%s')", scenery->size(),
           scenery->size() == 1 ? "box" : "boxes", message->header.frame_id.c_str());
  scenery_ = std::move(scenery);
  publishScenery();
  return true;
}

bool FrameWorker::takeDeliveries() {
  bool changed = false;
  for (auto& [key, delivery] : deliveries_) {
    if (!place(sourceName(key), delivery.frame->header.stamp, *delivery.frame)) continue;
    sources_.store(key, std::move(delivery.frame), delivery.received);
    changed = true;
  }
  deliveries_.clear();
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
    outputs_.holdLastPairs();  // this update is not published: its events are not the node's
    engine_.update(BoxFrame());
    publishWorld(sceneryHeader(), {});
  }
  for (const auto& [key, frames] : expired) {
    ingest_.upkeep().forget(key);
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
  const std::string& fixed_frame = ingest_.placement().fixedFrame();
  sources_.assemble(fixed_frame.empty() ? static_frame_ : fixed_frame, world_);
  for (const LeftOutSource& left_out : world_.left_out) refuseLeftOut(left_out);
  FrameAccount frame;
  frame.ms_conversion = millisecondsSince(start);
  const PairList* pairs = loadWorld();
  if (!pairs) return;
  for (const WorldMember& member : world_.members)
    if (sources_.accept(member.key)) status_.countProcessed();
  const BoxFrame boxes(spans_);
  frame.header = world_.header();
  frame.boxes = boxes.size();
  frame.sources = world_.members.size();
  frame.ms_message = outputs_.publishPairs(*pairs, frame.header);
  frame.ms_total = millisecondsSince(start);
  outputs_.publishEvents(engine_.events(), *pairs, frame.header);
  // The boxes just loaded, read where the sources keep them, and the scenery they meet.
  const BoxFrame scenery = scenery_ ? BoxFrame(scenery_->span()) : BoxFrame();
  const MarkerCounts markers =
      outputs_.publishMarkers(boxes, *pairs, frame.header, ingest_.upkeep().idNames(), &scenery);
  frame.marker_boxes = markers.drawn;
  frame.marker_boxes_omitted = markers.colliding_omitted;
  status_.frameComputed(frame, engine_.stats());
}

const PairList* FrameWorker::loadWorld() {
  const auto update = [this](const BoxFrame& inFrame) -> const PairList& {
    return engine_.update(inFrame);
  };
  const auto refused = [this](const SourceFrame& inFrame, const std::string& inReason) {
    status_.refuse(inFrame.header, inFrame.size(), inReason);
  };
  const PairList* pairs = nullptr;
  try {
    pairs = sap_broadphase::loadWorld(world_, sources_, spans_, update, refused);
  } catch (const TooManyPairs& refusal) {
    // No source is to blame: the world's frame as a whole has more pairs than ~max_pairs. The
    // sources keep their frames (the next delivery tries again), nothing is published for it,
    // and the engine, reset, answers the next frame.
    status_.refuse(world_.header(), BoxFrame(spans_).size(), refusal.what());
  }
  std::vector<SourceFramePtr> frames;
  if (pairs)
    for (const WorldMember& member : world_.members) frames.push_back(member.frame);
  // An update that threw leaves the scenery alone in the engine. Published before the pairs:
  // a query sent on receiving them is answered on their frame or a later one.
  publishWorld(pairs ? world_.header() : sceneryHeader(), std::move(frames));
  return pairs;
}

bool FrameWorker::place(const std::string& inName, const ros::Time& inStamp, SourceFrame& ioFrame) {
  const std::optional<PlacementRefusal> refusal = ingest_.placement().place(inStamp, ioFrame);
  if (!refusal) return true;
  if (refusal->kind == PlacementRefusal::Kind::kNoTransform)
    status_.skip(inName + " skipped: " + refusal->reason);
  else  // the frame's own transform is wrong: refused, as a wrong box is
    status_.refuse(ioFrame.header, ioFrame.size(), inName + ": " + refusal->reason);
  return false;
}

void FrameWorker::refuseLeftOut(const LeftOutSource& inLeftOut) {
  const SourceKey& key = inLeftOut.source.key;
  const SourceFrame& frame = *inLeftOut.source.frame;
  // The engine never sees a frame left out, yet its sender must learn what is wrong with its
  // boxes first: the engine's own check names them, as a load would.
  if (const auto problem = validate(BoxFrame(frame.span()))) {
    status_.refuse(frame.header, frame.size(), sourceName(key) + ": " + problem->message());
    sources_.refuse(key);
    return;
  }
  status_.refuse(frame.header, frame.size(), inLeftOut.reason);
}

}  // namespace sap_broadphase
