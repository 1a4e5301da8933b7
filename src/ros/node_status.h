// NodeStatus: what the node has done since start-up, told three ways: the `stats` topic (one
// message per computed or refused frame), /diagnostics (rates and warnings since the last
// report) and the log (refusals, skips, time-outs). Every thread of the node reports here.
#pragma once

#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>
#include <std_msgs/Header.h>

#include "sap_broadphase/FrameStats.h"
#include "sap_broadphase/core/broadphase.h"

namespace sap_broadphase {

/// What the node has counted since start-up, as NodeStatus keeps it.
struct NodeCounters {
  uint64_t received = 0;            // source frames received
  uint64_t processed = 0;           // source frames taken into the world
  uint64_t dropped = 0;             // source frames replaced before the worker took them
  uint64_t refused = 0;             // invalid frames, and sources left out of a frame
  uint64_t skipped = 0;             // source frames without a transform into ~fixed_frame
  uint64_t timed_out = 0;           // sources dropped after ~source_timeout of silence
  uint64_t lost = 0;                // MarkerArray messages lost in a subscriber queue
  uint64_t computed = 0;            // frames computed
  std::string last_refusal;         // why the last frame or source was refused
  std::string last_error;           // the last refusal, skip or time-out, for /diagnostics
  std::string refused_publishers;   // publishers of another type or MD5 sum, now
  uint32_t live_sources = 0;        // sources of the last computed frame's world (stats)
  uint32_t held_sources = 0;        // sources held now, each within its time-out
  uint32_t configured_sources = 0;  // topics of ~sources
  uint32_t static_boxes = 0;        // boxes of the scenery in force
  double last_ms_total = 0.0;       // latency of the last computed frame
  double max_ms_total = 0.0;        // largest latency since the last diagnostics report
};

/// One counter of the node: its FrameStats field and /diagnostics key ("" where it is not
/// shown). The table drives both; adding a counter is a row and a member of NodeCounters (and
/// its field in FrameStats.msg, which test_ros_units checks).
struct NodeCounterRow {
  const char* stats_field;
  const char* diagnostics_key;
  uint64_t NodeCounters::*counter;
  uint64_t FrameStats::*field;
};

/// The counters' table, in the order /diagnostics lists them.
const std::vector<NodeCounterRow>& nodeCounterRows();

/// The FrameStats fields the node fills from its own state besides the counters (header,
/// sources, marker counts, the gathering's time, ...): with the counters' rows and the engine
/// report's `topic` column (frame_report.h) they are every field of the message.
const std::vector<std::string>& nodeStatsFields();

/// Copies the engine's account of a frame into the stats message: every row of the report's
/// table whose `topic` names a field, phases folded into the message's coarser ones.
void fillEngineStats(const FrameReport& inEngine, FrameStats& outStats);

/// Times and counts of one computed frame that only the worker knows.
struct FrameAccount {
  std_msgs::Header header;
  std::size_t boxes = 0;
  std::size_t sources = 0;
  double ms_conversion = 0.0;  ///< gathering the sources' frames into the world's spans
  double ms_message = 0.0;     ///< filling and publishing `pairs`
  double ms_total = 0.0;       ///< from the gathering to `pairs` published
  uint32_t marker_boxes = 0;
  uint32_t marker_boxes_omitted = 0;
};

/// Thread-safe counters of the node, published as `stats` and /diagnostics.
class NodeStatus {
 public:
  /// Advertises `stats` on ioNode; /diagnostics is named after inPrivate's namespace.
  NodeStatus(ros::NodeHandle& ioNode, const ros::NodeHandle& inPrivate,
             const BroadphaseConfig& inEngine, int inLogPeriod);

  void countReceived();
  /// A source frame replaced by a newer one of the same source before the worker took it.
  void countDropped();
  void countProcessed();
  void setStaticBoxes(std::size_t inBoxes);
  /// The engine settings in force (axes and threads in every stats message).
  void setEngineConfig(const BroadphaseConfig& inEngine);
  /// Counts and logs a refused frame or source and publishes stats for it (any thread).
  void refuse(const std_msgs::Header& inHeader, std::size_t inBoxes, const std::string& inReason);
  /// Counts and logs a source frame that found no transform (any thread).
  void skip(const std::string& inMessage);
  /// Counts and logs inCount messages of a stateful source (MarkerArray: each message says what
  /// changed) lost in its subscriber queue before they were read (worker thread).
  void lose(uint64_t inCount, const std::string& inTopic);
  /// The publishers refused now for their type or MD5 sum, "topic: /publisher", named in
  /// /diagnostics (any thread).
  void setRefusedPublishers(const std::vector<std::string>& inNames);
  /// Counts and logs a source gone silent (worker thread): a WARN and the last error when
  /// inUnexpected (a stream broke off), else an INFO (a source that published once).
  void timeOut(const std::string& inMessage, bool inUnexpected);
  /// The sources the worker holds now (each within its time-out) of the inConfigured topics of
  /// ~sources (worker thread, every round): /diagnostics counts a source live only while it
  /// holds, and says so when none does.
  void setLiveSources(std::size_t inLive, std::size_t inConfigured);
  /// Counts a computed frame and publishes its stats with the engine's report.
  void frameComputed(const FrameAccount& inFrame, const FrameReport& inEngine);
  /// The ROS clock went back: the diagnostics' period and rate start again from now (worker
  /// thread).
  void restartClock();
  /// Publishes /diagnostics when its period has passed (worker thread).
  void updateDiagnostics() { diagnostics_.update(); }

 private:
  /// Stats of the counters as they are now (called with mutex_ held).
  FrameStats makeStats(const std_msgs::Header& inHeader, std::size_t inBoxes) const;
  /// The level and summary of /diagnostics (called with mutex_ held): WARN for new problems
  /// since the last report, or for a node that computed before and holds no source now.
  void summarize(diagnostic_updater::DiagnosticStatusWrapper& ioStatus) const;
  /// The /diagnostics status: rate, latency, drops, refusals, skips, time-outs, last error.
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& ioStatus);

  ros::Publisher stats_pub_;
  int log_period_;
  std::mutex mutex_;
  NodeCounters counters_;
  BroadphaseConfig engine_;  // settings in force: axes and threads of every stats message
  NodeCounters reported_;    // counters at the last /diagnostics report
  ros::Time reported_at_;    // ROS time: the frame rate follows /clock under use_sim_time
  diagnostic_updater::Updater diagnostics_;
};

}  // namespace sap_broadphase
