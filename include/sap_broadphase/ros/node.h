// BroadphaseNode: the latest frame of every source merged into one world (transformed into a
// fixed frame with tf2), tested against a latched static world; pairs, pair events, markers,
// stats and /diagnostics out from a worker thread; the compute_pairs service on its own
// spinner thread with its own engine; dynamic_reconfigure of the engine and marker settings.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <boost/thread/recursive_mutex.hpp>

#include "sap_broadphase/BoxArray.h"
#include "sap_broadphase/ComputePairs.h"
#include "sap_broadphase/FrameStats.h"
#include "sap_broadphase/PairArray.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/ros/node_params.h"
#include "sap_broadphase/ros/sources.h"

namespace dynamic_reconfigure {
template <class ConfigType>
class Server;
}  // namespace dynamic_reconfigure

namespace sap_broadphase {

class BroadphaseNodeConfig;  // generated from cfg/BroadphaseNode.cfg

/// The ROS face of the engine. All topic and service names are relative to the node handle
/// given, so they can be remapped or pushed into a namespace. Every thread it needs is its own
/// (worker, service spinner, tf listener); the caller only spins ioNode's queue.
class BroadphaseNode {
 public:
  /// Subscribes, advertises and starts the worker and the service thread. The source callbacks
  /// run on ioNode's callback queue (spin it, e.g. ros::spin()); inPrivate names the node for
  /// /diagnostics and serves dynamic_reconfigure on its callback queue.
  BroadphaseNode(ros::NodeHandle& ioNode, const ros::NodeHandle& inPrivate,
                 const NodeParams& inParams);
  /// As above with the private handle "~" of the process.
  BroadphaseNode(ros::NodeHandle& ioNode, const NodeParams& inParams);
  /// Stops the service thread and the worker (a frame in progress is finished first).
  ~BroadphaseNode();
  BroadphaseNode(const BroadphaseNode&) = delete;
  BroadphaseNode& operator=(const BroadphaseNode&) = delete;

 private:
  /// Counters since start-up; guarded by mutex_.
  struct Counters {
    uint64_t received = 0;       // source frames received
    uint64_t processed = 0;      // source frames taken into the world
    uint64_t dropped = 0;        // source frames replaced before the worker took them
    uint64_t refused = 0;        // invalid frames, and sources left out of a frame
    uint64_t skipped = 0;        // source frames without a transform into ~fixed_frame
    uint64_t timed_out = 0;      // sources dropped after ~source_timeout of silence
    uint64_t computed = 0;       // frames computed
    std::string last_refusal;    // why the last frame or source was refused
    std::string last_error;      // the last refusal, skip or time-out, for /diagnostics
    uint32_t live_sources = 0;   // sources of the last computed frame's world
    uint32_t static_boxes = 0;   // boxes of the scenery in force
    double last_ms_total = 0.0;  // latency of the last computed frame
    double max_ms_total = 0.0;   // largest latency since the last diagnostics report
  };
  /// A frame waiting for the worker: the latest of its source wins.
  struct Delivery {
    BoxArrayConstPtr msg;
    ros::Time received;
  };

  /// Source callback: cheap shape check, then hands the frame to the worker (latest wins per
  /// source, i.e. per topic and publisher).
  void onBoxes(const std::string& inTopic, const ros::MessageEvent<BoxArray const>& inEvent);
  /// static_boxes callback: hands the scenery to the worker.
  void onStaticBoxes(const BoxArrayConstPtr& inMsg);
  /// Service callback: converts, validates and computes on the service's own engine.
  bool onComputePairs(ComputePairs::Request& inRequest, ComputePairs::Response& outResponse);
  /// dynamic_reconfigure callback: checks ioConfig and hands accepted settings to the worker
  /// and the service thread; refused settings are logged and ioConfig is set back to the
  /// settings in force, which the server then reports to its clients.
  void onReconfigure(BroadphaseNodeConfig& ioConfig, uint32_t inLevel);
  /// Takes reconfigured settings into force between two frames (worker thread): a new engine
  /// (scenery declared again) when the engine settings changed, markers advertised or not.
  void applySettings(const NodeParams& inSettings);

  /// The worker thread: waits for deliveries (or the next ~rate tick), takes them into the
  /// world, computes, publishes; between frames expires silent sources and reports diagnostics.
  void workerLoop();
  /// Converts, validates and transforms one message (with the transform at inWhen) into
  /// outBoxes (worker thread). False, with the refusal or skip already counted, when the
  /// message cannot join the world.
  bool ingest(const std::string& inWhat, const BoxArray& inMsg, const ros::Time& inWhen,
              BoxSet& outBoxes);
  /// Replaces the scenery of the engine (worker thread).
  void ingestStatic(const BoxArray& inMsg);
  /// Drops silent sources, counts and logs each once (worker thread).
  void expireSources();
  /// Merges the sources, computes and publishes one frame (worker thread).
  void computeFrame();
  /// Publishes what changed since the previous frame, while someone listens (worker thread).
  void publishEvents(const PairList& inPairs, const std_msgs::Header& inHeader);
  /// Counts and logs a refusal and publishes stats for it (any thread).
  void refuse(const std_msgs::Header& inHeader, std::size_t inBoxes, const std::string& inReason);
  /// Counts and logs a source frame skipped for lack of a transform (worker thread).
  void skip(const std::string& inWhat, const std::string& inReason);
  /// Stats of the counters as they are now.
  FrameStats makeStats(const std_msgs::Header& inHeader, std::size_t inBoxes);
  /// The /diagnostics status: rate, latency, drops, refusals, skips, time-outs, last error.
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& ioStatus);

  // The settings in force; the worker changes the run-time ones under mutex_ (it alone writes,
  // so it reads them without the lock; other threads read them under mutex_).
  NodeParams params_;
  ros::NodeHandle node_;  // to advertise `markers` when they are switched on at run time
  std::vector<ros::Subscriber> source_subs_;
  ros::Subscriber static_sub_;
  ros::Publisher pairs_pub_;
  ros::Publisher events_pub_;
  ros::Publisher markers_pub_;
  ros::Publisher stats_pub_;

  // tf2 (only with a ~fixed_frame): the listener has its own thread.
  std::unique_ptr<tf2_ros::Buffer> tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;

  // Service: own queue and thread so a long topic frame never delays it.
  ros::CallbackQueue service_queue_;
  ros::ServiceServer service_;
  std::optional<ros::AsyncSpinner> service_spinner_;
  Broadphase service_engine_;  // used only by the service thread (rebuilt by it on reconfigure)
  BoxSet service_boxes_;       // its conversion buffer
  CapacityWatch service_watch_;

  // Worker hand-off: guarded by mutex_.
  std::mutex mutex_;
  std::condition_variable wake_;
  std::map<SourceKey, Delivery> pending_;
  BoxArrayConstPtr pending_static_;
  bool stopping_ = false;
  Counters counters_;
  std::optional<NodeParams> pending_settings_;              // for the worker
  std::optional<BroadphaseConfig> pending_service_config_;  // for the service thread

  // dynamic_reconfigure: the server (with a mutex of ours, so that giving it the settings in
  // force cannot deadlock with a client's update) and the settings last accepted (its
  // callback's own).
  boost::recursive_mutex reconfigure_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<BroadphaseNodeConfig>> reconfigure_;
  NodeParams accepted_;

  // Worker-owned state.
  Broadphase engine_;
  SourceSet sources_;
  BoxSet static_boxes_;               // the scenery, declared again to a rebuilt engine
  std::vector<uint32_t> static_ids_;  // sorted ids of the scenery, for the id check
  std::string static_frame_;          // frame of the scenery without ~fixed_frame
  BoxSet converted_;                  // conversion buffer, swapped into the sources
  CapacityWatch converted_watch_;
  BoxSet world_;  // union of the sources when there are several
  CapacityWatch world_watch_;
  PairList previous_pairs_;  // for pair_events, kept while someone listens
  bool previous_pairs_valid_ = false;
  diagnostic_updater::Updater diagnostics_;
  Counters reported_;  // counters at the last /diagnostics report (worker thread)
  ros::WallTime reported_at_;
  std::thread worker_;
};

}  // namespace sap_broadphase
