// WorldSnapshot: the world as query_boxes sees it, the last frame the worker computed and the
// scenery, published by the worker once a frame and read by the query threads through a
// shared_ptr: a query never waits for the frame in progress. Immutable once built, but for
// the index of its frame: built by the worker before it publishes the snapshot while queries
// are coming (the last snapshot was asked), so that queries only read; otherwise by the first
// query that needs it (std::call_once; the others wait for that build, never for a frame).
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <vector>

#include <std_msgs/Header.h>

#include "sap_broadphase/core/broadphase.h"
#include "sources.h"

namespace sap_broadphase {

/// The scenery's index for queries, built by the worker when the scenery (or the engine's
/// configuration) changes, shared by every snapshot until then.
class SceneryIndex {
 public:
  /// Indexes inScenery (null: none) with inConfig's threads; inScenery was accepted by the
  /// worker's engine.
  SceneryIndex(SourceFramePtr inScenery, const BroadphaseConfig& inConfig);
  /// Hits of inQueries (valid) in the scenery, appended to ioHits.
  void query(const BoxFrame& inQueries, QueryHitList& ioHits) const;

 private:
  SourceFramePtr scenery_;  // its boxes, read where they lie
  Broadphase index_;        // the scenery declared: its own index
};

class WorldSnapshot {
 public:
  /// The frames of inFrames (the world's sources, as the engine loaded them; none: the scenery
  /// alone) with inHeader, the frame's, and the scenery of inScenery (never null).
  WorldSnapshot(const std_msgs::Header& inHeader, std::vector<SourceFramePtr> inFrames,
                std::shared_ptr<const SceneryIndex> inScenery, const BroadphaseConfig& inConfig);
  WorldSnapshot(const WorldSnapshot&) = delete;
  WorldSnapshot& operator=(const WorldSnapshot&) = delete;

  /// Broadphase::query() on this world: what overlaps inQueries in the frame and the scenery,
  /// sorted by (query id, world id). Throws InvalidBoxes naming a bad query box. Any thread.
  QueryHitList query(const BoxFrame& inQueries) const;
  /// Indexes the frame's boxes now, unless done (the worker, before publishing the snapshot).
  void index() const;
  /// True once a query has read this snapshot: the next one is likely to be asked too.
  bool asked() const { return asked_.load(std::memory_order_relaxed); }
  /// The header of the frame (its newest source stamp, its frame id).
  const std_msgs::Header& header() const { return header_; }

 private:
  std_msgs::Header header_;
  std::vector<SourceFramePtr> frames_;  // keep the spans' boxes alive, unchanged
  std::vector<BoxSpan> spans_;
  std::shared_ptr<const SceneryIndex> scenery_;
  mutable std::once_flag indexed_;
  mutable std::atomic<bool> asked_{false};
  mutable Broadphase frame_index_;  // the frame's boxes declared as its scenery, once
};

}  // namespace sap_broadphase
