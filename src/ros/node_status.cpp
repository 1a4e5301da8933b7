// NodeStatus: counters, `stats` and /diagnostics.
#include "node_status.h"

#include <algorithm>
#include <map>
#include <set>
#include <type_traits>
#include <variant>

#include <boost/make_shared.hpp>

namespace sap_broadphase {

namespace {

/// A field of FrameStats that the engine's report feeds.
using StatsMember = std::variant<uint32_t FrameStats::*, uint8_t FrameStats::*,
                                 double FrameStats::*, std::string FrameStats::*>;

/// The FrameStats fields the report's `topic` column may name: the message's side of the
/// table (C++ has no names of members; test_ros_units checks both sides agree).
const std::map<std::string, StatsMember>& engineStatsMembers() {
  static const std::map<std::string, StatsMember> members = {
      {"boxes", &FrameStats::boxes},
      {"pairs", &FrameStats::pairs},
      {"primary_axis", &FrameStats::primary_axis},
      {"secondary_axis", &FrameStats::secondary_axis},
      {"dispersion_primary", &FrameStats::dispersion_primary},
      {"dispersion_secondary", &FrameStats::dispersion_secondary},
      {"axes_swapped", &FrameStats::axes_swapped},
      {"path", &FrameStats::path},
      {"threads", &FrameStats::threads},
      {"slabs", &FrameStats::slabs},
      {"skin", &FrameStats::skin},
      {"skin_choice", &FrameStats::skin_choice},
      {"moved_boxes", &FrameStats::moved_boxes},
      {"max_displacement", &FrameStats::max_displacement},
      {"static_boxes", &FrameStats::static_boxes},
      {"ms_history", &FrameStats::ms_history},
      {"ms_sort", &FrameStats::ms_sort},
      {"ms_candidates", &FrameStats::ms_candidates},
      {"ms_pairing", &FrameStats::ms_pairing},
      {"ms_static", &FrameStats::ms_static},
      {"ms_output", &FrameStats::ms_output},
      {"ms_total", &FrameStats::ms_total},
  };
  return members;
}

/// Writes one report value into its message field: names as text, numbers converted to the
/// field's type; a field fed by several rows (a phase folded into a coarser one) adds them.
/// A `topic` the message side does not know writes nothing (test_ros_units names it).
template <typename Value>
void writeStatsValue(const ReportField& inField, Value inValue, bool inAdd, FrameStats& ioStats) {
  const auto member = engineStatsMembers().find(inField.topic);
  if (member == engineStatsMembers().end()) return;
  std::visit(
      [&](auto inMember) {
        auto& target = ioStats.*inMember;
        using Target = std::decay_t<decltype(target)>;
        if constexpr (std::is_same_v<Target, std::string>) {
          target = reportValueText(inField.unit, inValue);
        } else if constexpr (std::is_arithmetic_v<Value>) {
          const Target value = static_cast<Target>(inValue);
          target = inAdd ? static_cast<Target>(target + value) : value;
        }
      },
      member->second);
}

}  // namespace

const std::vector<NodeCounterRow>& nodeCounterRows() {
  static const std::vector<NodeCounterRow> rows = {
      {"frames_computed", "frames computed", &NodeCounters::computed, &FrameStats::frames_computed},
      {"frames_received", "source frames received", &NodeCounters::received,
       &FrameStats::frames_received},
      {"frames_dropped", "source frames dropped", &NodeCounters::dropped,
       &FrameStats::frames_dropped},
      {"frames_refused", "refusals", &NodeCounters::refused, &FrameStats::frames_refused},
      {"frames_skipped", "frames skipped (no transform)", &NodeCounters::skipped,
       &FrameStats::frames_skipped},
      {"sources_timed_out", "sources timed out", &NodeCounters::timed_out,
       &FrameStats::sources_timed_out},
      {"messages_lost", "MarkerArray messages lost", &NodeCounters::lost,
       &FrameStats::messages_lost},
      {"frames_processed", "", &NodeCounters::processed, &FrameStats::frames_processed},
  };
  return rows;
}

const std::vector<std::string>& nodeStatsFields() {
  static const std::vector<std::string> fields = {
      "header",       "static_world_boxes", "ms_conversion",        "sources",
      "last_refusal", "marker_boxes",       "marker_boxes_omitted",
  };
  return fields;
}

void fillEngineStats(const FrameReport& inEngine, FrameStats& outStats) {
  std::set<std::string> written;
  forEachReportField(inEngine, [&](const ReportField& inField, auto inValue) {
    if (*inField.topic == '\0') return;  // a field the topic leaves out
    const bool add = !written.insert(inField.topic).second;
    writeStatsValue(inField, inValue, add, outStats);
  });
}

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
  for (const NodeCounterRow& row : nodeCounterRows()) stats.*row.field = counters_.*row.counter;
  stats.sources = counters_.live_sources;
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
  for (const NodeCounterRow& row : nodeCounterRows())
    if (*row.diagnostics_key != '\0') ioStatus.add(row.diagnostics_key, counters_.*row.counter);
  ioStatus.add("refused publishers", counters_.refused_publishers);
  ioStatus.add("last error", counters_.last_error);
  reported_ = counters_;
  reported_at_ = now;
  counters_.max_ms_total = 0.0;
}

}  // namespace sap_broadphase
