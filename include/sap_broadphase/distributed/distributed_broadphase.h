// The broad phase over MPI ranks: slabs along one axis, one Broadphase per slab, each pair
// reported exactly once (docs/DISTRIBUTED.md).
#pragma once

#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase::distributed {

/// What the slab cuts balance.
enum class SlabBalance : uint8_t {
  kCount,  ///< boxes per slab (from a sample of box positions)
  kCost,   ///< measured engine time per slab (the sample weighted by its slab's last time)
};

/// Where a frame's pairs end up.
enum class PairDelivery : uint8_t {
  kToOwners,      ///< every rank gets the pairs that involve its own boxes, sorted
  kGatherAtRoot,  ///< the root rank gets every pair, sorted; the others get none
};

/// What a caller may tune.
struct DistributedConfig {
  BroadphaseConfig engine;  ///< each rank's engine on its slab (threads, method, skips)
  int slab_axis = 0;        ///< the axis cut into slabs (0 = x, 1 = y, 2 = z)
  SlabBalance balance = SlabBalance::kCount;
  /// Slabs are re-cut when the fullest slab (kCount: boxes; kCost: engine time) exceeds the
  /// mean by more than this fraction. Between re-cuts ranks keep the boxes they received.
  double recut_imbalance = 0.25;
  std::size_t samples_per_rank = 1024;  ///< box positions each rank gives to a cut
};

/// What one frame cost on this rank. Times are milliseconds of wall clock.
struct DistributedReport {
  std::size_t local_boxes = 0;      ///< boxes this rank passed to update()
  std::size_t slab_boxes = 0;       ///< boxes in this rank's slab (own + received)
  std::size_t resident_boxes = 0;   ///< boxes received from other ranks, kept across frames
  std::size_t border_boxes = 0;     ///< the border set: received boxes + own ones they reach
  std::size_t boxes_sent = 0;       ///< box records sent to other ranks this frame
  std::size_t removals_sent = 0;    ///< "box left your slab" notices sent this frame
  std::size_t own_pairs = 0;        ///< pairs among this rank's own boxes
  std::size_t cross_pairs = 0;      ///< pairs of boxes of two owners that this slab owns
  std::size_t pairs_returned = 0;   ///< pairs update() returned on this rank
  uint64_t box_bytes_sent = 0;      ///< bytes of box records and removals to other ranks
  uint64_t pair_bytes_sent = 0;     ///< bytes of pairs delivered to other ranks
  uint64_t control_bytes_sent = 0;  ///< sizes, samples and balance figures sent
  bool recut = false;               ///< the slabs were cut (again) this frame
  double imbalance = 1.0;      ///< fullest slab / mean slab (boxes; kCost: engine time), all ranks
  double ms_cut = 0.0;         ///< sampling and agreeing on the cuts (re-cut frames only)
  double ms_exchange = 0.0;    ///< deciding what to send, the exchange, merging what came
  double ms_assemble = 0.0;    ///< building the border set
  double ms_own_engine = 0.0;  ///< the Broadphase on the own boxes
  double ms_border_engine = 0.0;  ///< the Broadphase on the border set
  double ms_engine = 0.0;         ///< both
  double ms_filter = 0.0;         ///< the ownership rule and the ids
  double ms_deliver = 0.0;        ///< sending pairs to their owners or the root, and sorting
  double ms_total = 0.0;
  FrameReport engine;         ///< the own boxes' engine's report
  FrameReport border_engine;  ///< the border set's engine's report
};

/// The distributed broad phase. Every rank of the communicator calls update() on every frame
/// with the boxes of its own bodies (any count, zero included); box ids are unique over all
/// ranks. Each rank finds the pairs among its own boxes with a Broadphase on them as given
/// (so coherence across frames works as in one process). Pairs of boxes of two owners: rank r
/// computes slab r of the slab axis; it receives the other ranks' boxes that overlap its slab,
/// runs a second Broadphase on them and the own boxes they reach, and keeps each pair whose
/// later-starting box (larger min on the slab axis) starts in slab r, so each pair is found by
/// exactly one rank.
/// The input is trusted: validate() each rank's boxes at the edge first. Ranks keep the boxes
/// they received; a box is sent again only when its bounds, group or mask changed or it newly
/// overlaps a slab.
class DistributedBroadphase {
 public:
  /// inCommunicator is duplicated (the caller's messages never meet ours). Collective.
  explicit DistributedBroadphase(MPI_Comm inCommunicator,
                                 const DistributedConfig& inConfig = DistributedConfig());
  ~DistributedBroadphase();
  DistributedBroadphase(const DistributedBroadphase&) = delete;
  DistributedBroadphase& operator=(const DistributedBroadphase&) = delete;

  /// One frame, collective. Returns the pairs inDelivery asks for, as ids with a < b in
  /// canonical (a, b) order; valid until the next update().
  const PairList& update(const BoxSet& inLocalBoxes,
                         PairDelivery inDelivery = PairDelivery::kToOwners, int inRoot = 0);
  /// Statistics of the last update() on this rank.
  const DistributedReport& stats() const;
  /// The slab borders in force: slab s is [cuts[s-1], cuts[s]) (slab 0 from -inf, the last
  /// to +inf inclusive); ranks() - 1 values, non-decreasing.
  const std::vector<double>& cuts() const;
  /// The slab (= rank) that holds coordinate inX of the slab axis under the cuts in force.
  int slabOf(double inX) const;
  /// The rank where a body with these bounds on the slab axis costs no exchange: the slab
  /// holding its centre. A simulation that migrates its bodies there (as LAMMPS-style codes
  /// do) sends only the boxes that overlap a neighbour slab.
  int homeRank(double inMin, double inMax) const;
  /// This process's rank and the number of ranks.
  int rank() const;
  int ranks() const;
  /// Forgets the cuts and the boxes kept from other ranks; the next update() starts afresh.
  /// Collective.
  void reset();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sap_broadphase::distributed
