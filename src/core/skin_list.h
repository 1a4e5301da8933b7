// Skin reuse: the neighbour-list idea of molecular dynamics (LAMMPS `neigh_modify check`,
// HOOMD's buffer) applied to boxes.
//
// One sweep runs on boxes inflated by skin/2 on every side and its pairs are kept as
// candidates. While every box of a later frame lies inside its inflated box of that sweep, two
// boxes that overlap now also overlapped inflated, so they are among the candidates: testing
// the candidates exactly gives every pair. Containment is checked with plain comparisons, so
// no rounding argument is needed; a box that left its inflated box (moved more than about
// skin/2), a new, removed or reordered id, or changed groups/masks force a new sweep.
#pragma once

#include <cstdint>
#include <vector>

#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase {

class SkinList {
 public:
  /// True when inBoxes can be answered from the kept candidates (see above).
  bool covers(const BoxSet& inBoxes, int inThreads) const;
  /// Writes into outInflated the boxes of inBoxes grown by inSkin / 2 on every side (rounded
  /// outward) and remembers them as the reference of the next candidates.
  void inflate(const BoxSet& inBoxes, double inSkin, BoxSet& outInflated);
  /// Keeps inCandidates (pairs of the inflated boxes, canonical order) as the candidates.
  void adopt(const BoxSet& inBoxes, const PairList& inCandidates);
  /// The candidates that overlap exactly in inBoxes (filters are already honoured by the
  /// candidates), in canonical order.
  void collect(const BoxSet& inBoxes, int inThreads, PairList& outPairs);
  /// True while candidates are kept (after adopt(), until clear() or the next inflate()).
  bool valid() const { return valid_; }
  /// Number of candidate pairs kept.
  std::size_t candidates() const { return candidate_indexes_.size(); }
  /// Forgets the candidates (the next frame sweeps).
  void clear() { valid_ = false; }

 private:
  BoxSet reference_;  // the inflated boxes of the last sweep (ids, groups, masks included)
  std::vector<std::pair<uint32_t, uint32_t>> candidate_indexes_;  // box indexes, canonical
  std::vector<PairList> per_thread_;
  bool valid_ = false;
};

}  // namespace sap_broadphase
