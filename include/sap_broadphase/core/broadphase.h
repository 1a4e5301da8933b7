// The broad phase, one frame at a time: update() loads the frame, plans it and runs one
// strategy, which returns the sorted pairs. The plan's strategies: the last pairs again for an
// unchanged frame; the candidates kept under a skin when every box is still inside its grown
// box; the small-frame kernel (a grid of one-axis sweeps, one thread) for frames below
// parallel_min_boxes and for every frame on one thread; else the paper's sweep (keys ->
// parallel radix sort -> candidates -> pairing), sequential or parallel. Box queries, contact
// events and declared scenery are answered beside the frame.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/config.h"
#include "sap_broadphase/core/frame_report.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase {

/// The stateful broad phase: keeps partition bounds B and the sweep axes across frames, owns
/// every buffer (no allocation per frame once sizes are stable). Not thread-safe: one frame at
/// a time per instance; between frames, query() may run on other threads (see there).
class Broadphase {
 public:
  explicit Broadphase(const BroadphaseConfig& inConfig = BroadphaseConfig());
  ~Broadphase();
  Broadphase(Broadphase&&) noexcept;
  Broadphase& operator=(Broadphase&&) noexcept;

  /// Computes every overlapping pair of the frame's boxes (closed intervals, filters
  /// honoured), as ids with a < b in canonical (a, b) order. The reference stays valid until
  /// the next update(). The frame is read once, as the engine copies it (it keeps a copy of
  /// every frame anyway, to know what moved), and checked on the way: a NaN bound, min > max,
  /// a repeated id (across spans too), an id that does not fit 32 bits or too many boxes throw
  /// InvalidBoxes naming the lowest bad box as validate() does; the engine is then as after
  /// reset(), except for events() (see there). A frame with more than config().max_pairs pairs
  /// throws TooManyPairs (pair_set.h) once they are found past the bound, and leaves the engine
  /// the same way, its pair buffers given back. The frame's memory is read only during the
  /// call.
  const PairList& update(const BoxFrame& inFrame);
  /// What changed between the pair lists of the last two update()s: `began` holds the pairs of
  /// the last list absent from the one before, `ended` those of the one before absent from the
  /// last, both canonical (as update()'s list). The first update() after construction or
  /// reset() has every pair begin and none end. An update() that threw reports no events, and
  /// the next update() that returns compares with the last list returned before it (a refused
  /// frame does not end and restart every contact). Scenery changed by setStaticBoxes() or
  /// clearStaticBoxes() shows at the next update(): its pairs with the old scenery end, those with
  /// the new one begin. A frame that reuses the last list (nothing moved) has none. Found by one
  /// merge of the two sorted lists (the last one is kept by swapping buffers, not copied); valid
  /// until the next update() or reset().
  const ContactEvents& events() const;
  /// Declares scenery: boxes that stay put until replaced, checked as update() checks a frame
  /// (a bad box throws InvalidBoxes and the scenery is unchanged). They are
  /// indexed once, here; every later update() reports the pairs among its boxes and between
  /// its boxes and the scenery, never scenery x scenery pairs (as the static bodies of Box2D,
  /// Jolt and Bullet). Ids of update()'s boxes must differ from the scenery's ids. Replaces
  /// any earlier scenery.
  void setStaticBoxes(const BoxFrame& inStaticBoxes);
  /// Forgets the scenery.
  void clearStaticBoxes();
  /// What overlaps each of inQueries in the world: the boxes of the last update() that
  /// returned, plus the declared scenery. Every world box that overlaps a query box (closed
  /// intervals, as update()'s pairs) and passes the group/mask filter with it both ways, as
  /// {query box's id, world box's id}, sorted by (query id, world id). The query boxes' ids
  /// name only them: number them 0..m-1 to get query indexes; they may equal world ids.
  /// Query boxes are checked as validate() does (a NaN bound, min > max, a repeated id): a bad
  /// one throws InvalidBoxes naming it, and the engine is unchanged. Before the first update(),
  /// and after an update() that threw, the world is the scenery alone; reset() keeps it.
  ///
  /// Threads: query() only reads the engine, so any number of queries may run at the same
  /// time, from any threads, together with stats(), config() and staticBoxCount(); none may run
  /// while update(), setStaticBoxes(), clearStaticBoxes(), reset() or an assignment runs on the
  /// same engine (the caller orders them, e.g. with a shared mutex: shared for queries,
  /// exclusive for the rest). Each query uses up to config().threads OpenMP threads.
  ///
  /// Cost: a few query boxes are answered by scanning the frame (one pass over it, about 3 ms
  /// at 2^20 boxes on 2 cores); once a frame's scans have cost about as much as an index of the
  /// frame, the index is built (once per frame, by the query that needs it) and answers the
  /// rest of the frame's queries in about a microsecond a query box. The scenery is always
  /// answered from its own index.
  QueryHitList query(const BoxFrame& inQueries) const;
  /// Number of declared static boxes.
  std::size_t staticBoxCount() const;
  /// Statistics of the last update().
  const FrameReport& stats() const;
  /// The configuration in force (axes change when swapped).
  const BroadphaseConfig& config() const;
  /// Forgets temporal state (partition bounds, the last pair list of events()); the next frame
  /// starts as a first frame, its events have every pair begin.
  void reset();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sap_broadphase
