// Box queries against the last frame: "which boxes of the frame overlap these boxes", between
// frames, from any thread (Broadphase::query).
//
// The frame is the frame history's copy (frame_history.h), so a query needs nothing the frame
// did not already keep. A few query boxes are answered by scanning that copy, which costs one
// pass over the frame; many are answered by an index of the frame (the exact grid of
// static_index.h), built at most once per frame, on the first query that needs it. Which one
// is the rent-or-buy rule: the frame is scanned until the scans of this frame have cost as
// much as building the index would, then the index is built and answers every later query of
// the frame. A frame asked one box never pays for an index; a frame asked thousands pays for
// one index and no more than as much again in scans.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <mutex>

#include "core/frame/box_columns.h"
#include "core/strategies/static_index.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase {

class FrameQuery {
 public:
  /// Queries now ask about inFrame (kept by reference: the caller keeps it unchanged until the
  /// next setFrame() or clear()). Forgets the last frame's index (its memory is kept).
  void setFrame(const BoxColumns& inFrame);
  /// Queries now find nothing.
  void clear();
  /// Gives back the index's memory (after a burst of large frames; the next index sizes it).
  void releaseMemory() { index_ = StaticIndex(); }
  /// Appends {query id, frame id} for every frame box that overlaps a box of inQueries
  /// (closed intervals) and passes the group/mask filter both ways, in any order. inQueries
  /// are valid (validate()). May run concurrently with other query() calls, never with
  /// setFrame() or clear().
  void query(const BoxColumns& inQueries, PairList& outHits) const;
  /// True once this frame's index has been built (for tests and benchmarks).
  bool indexed() const { return indexed_.load(std::memory_order_acquire); }

 private:
  bool shouldIndex(std::size_t inQueries) const;
  void buildIndex() const;
  void scan(const BoxColumns& inQueries, PairList& outHits) const;

  const BoxColumns* frame_ = nullptr;
  // The index is built by whichever concurrent query first needs it; the others wait on the
  // mutex, then read it without a lock once indexed_ says it is complete.
  mutable std::mutex index_mutex_;
  mutable StaticIndex index_;
  mutable std::atomic<bool> indexed_{false};
  // Query boxes answered by scanning this frame: each cost one pass over it.
  mutable std::atomic<std::size_t> scanned_queries_{0};
};

/// Broadphase::query() for valid inQueries: the hits in the last frame (inFrame) and in the
/// declared scenery (inScenery; its ids differ from the frame's), sorted by (query id, world
/// id), on the threads of the runner's scope, each hit as {query id, world id} (the facade hands
/// them out as QueryHits).
PairList answerQueries(const BoxColumns& inQueries, const FrameQuery& inFrame,
                       const StaticIndex& inScenery);

}  // namespace sap_broadphase
