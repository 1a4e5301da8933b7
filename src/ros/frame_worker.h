// FrameWorker: the thread that turns the sources' latest frames into frames of the world. It
// waits for deliveries (or the next ~rate tick, in ROS time), takes them into the world,
// computes with its engine against the latched scenery, and publishes; between frames it takes
// reconfigured settings into force, expires silent sources and reports diagnostics.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <ros/ros.h>

#include "frame_outputs.h"
#include "node_params.h"
#include "node_status.h"
#include "sap_broadphase/BoxArray.h"
#include "sap_broadphase/core/broadphase.h"
#include "source_ingest.h"
#include "sources.h"
#include "world_snapshot.h"

namespace sap_broadphase {

/// What a query answers and the frame it was answered on.
struct QueryAnswer {
  QueryHitList hits;
  std_msgs::Header header;  ///< the world's frame: its newest source stamp, its frame id
};

class FrameWorker {
 public:
  /// Starts the thread; ioIngest, ioOutputs and ioStatus must outlive the worker.
  FrameWorker(const NodeParams& inParams, SourceIngest& ioIngest, FrameOutputs& ioOutputs,
              NodeStatus& ioStatus);
  /// Stops the thread (a frame in progress is finished first).
  ~FrameWorker();
  FrameWorker(const FrameWorker&) = delete;
  FrameWorker& operator=(const FrameWorker&) = delete;

  /// Something arrived: the worker looks at the ingest again (any thread).
  void wake();
  /// Reconfigured settings, taken into force before the next frame (any thread).
  void reconfigure(const NodeParams& inSettings);
  /// What overlaps inQueries (checked, in the world's frame) in the world: the last frame
  /// computed plus the scenery (Broadphase::query's answer), and that frame's header. Any
  /// thread; answered from the snapshot of the last frame, so it never waits for the frame in
  /// progress (only, once a frame, for the index of the frame it reads).
  QueryAnswer query(const BoxFrame& inQueries) const;

 private:
  /// Waits for work, takes it in, computes; until the destructor says stop.
  void run();
  /// Waits until woken or inDeadline (ROS time), or until the clock goes back more than
  /// inPeriod before it. False when the worker must stop.
  bool waitUntil(const ros::Time& inDeadline, const ros::Duration& inPeriod);
  /// A new engine (scenery declared again) when the engine settings changed; markers.
  void applySettings(const NodeParams& inSettings);
  /// Takes the deliveries into the sources. True when the world changed.
  bool takeDeliveries();
  /// Replaces the engine's scenery once tf2 can place it. True when the world changed.
  bool takeScenery();
  /// Drops silent sources, counts and logs each once; when the last one goes, the world is the
  /// scenery alone (for queries).
  void expireSources();
  /// The ROS clock went back to inNow: receipt times and time-outs start again from it.
  void restartClock(const ros::Time& inNow);
  /// The header of a world that is the scenery alone: stamp 0, the world's frame.
  std_msgs::Header sceneryHeader() const;
  /// Counts and logs an exception (inWhat) that ended a round of the loop; a new engine.
  void recoverFrom(const std::string& inWhat);
  /// Hands the sources' frames to the engine, publishes the pairs and the frame's accounts.
  void computeFrame();
  /// The engine on the spans of world_ (sources.h's loadWorld): a refused source falls back on
  /// its last accepted frame or leaves, and the world is loaded again. The pairs, or null when
  /// no source is left. Queries see the world before the pairs leave.
  const PairList* loadWorld();
  /// Moves ioFrame (of the source or scenery named inName) into ~fixed_frame at inStamp. False,
  /// with the frame skipped (no transform) or refused (one not finite) counted and named, when
  /// it cannot be placed.
  bool place(const std::string& inName, const ros::Time& inStamp, SourceFrame& ioFrame);
  /// Queries now see the frames inFrames (none: the scenery alone) with inHeader; while
  /// queries are coming, indexed first (on this thread), so that they only read.
  void publishWorld(const std_msgs::Header& inHeader, std::vector<SourceFramePtr> inFrames);
  /// True when the snapshot in force was read by a query.
  bool queriesComing() const;
  /// The scenery (scenery_) indexed for queries, with the engine settings in force; queries
  /// see it with the last frame published.
  void publishScenery();
  /// Counts and names a source the world leaves out for its frame_id: for its boxes first, when
  /// they are no boxes (the frame then leaves as one the engine refuses), else for its frame.
  void refuseLeftOut(const LeftOutSource& inLeftOut);

  NodeParams params_;  // the settings in force (worker thread only)
  SourceIngest& ingest_;
  FrameOutputs& outputs_;
  NodeStatus& status_;

  std::mutex mutex_;  // guards the hand-off below
  std::condition_variable wake_;
  bool woken_ = false;
  bool stopping_ = false;
  std::optional<NodeParams> pending_settings_;
  ros::Time last_now_;  // ROS time of the last round (worker thread): a later one before it is a
                        // jump back in time

  Broadphase engine_;  // the worker's alone: queries read the snapshot below
  // The world as queries see it: replaced by the worker (under the mutex, a pointer's copy),
  // read by the query threads, which keep the one they took until they answered.
  mutable std::mutex snapshot_mutex_;
  std::shared_ptr<const WorldSnapshot> snapshot_;
  std::shared_ptr<const SceneryIndex> scenery_index_;  // shared by the snapshots (worker)
  std_msgs::Header snapshot_header_;                   // of the last published (worker)
  std::vector<SourceFramePtr> snapshot_frames_;        // of the last published (worker)
  SourceSet sources_;
  std::map<SourceKey, Delivery> deliveries_;
  SourceFramePtr scenery_;      // the scenery, declared again to a rebuilt engine
  std::string static_frame_;    // frame of the scenery without ~fixed_frame
  WorldAssembly world_;         // the sources of the frame being computed (worker thread)
  std::vector<BoxSpan> spans_;  // their boxes as the engine reads them, one span a source
  std::thread thread_;
};

}  // namespace sap_broadphase
