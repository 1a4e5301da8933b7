// Skin reuse: the neighbour-list idea of molecular dynamics (LAMMPS `neigh_modify check`,
// HOOMD's buffer) applied to boxes.
//
// One sweep runs on boxes inflated by skin/2 on every side and its pairs are kept as
// candidates. While every box of a later frame lies inside its inflated box of that sweep, two
// boxes that overlap now also overlapped inflated, so they are among the candidates: testing
// the candidates exactly gives every pair. Containment is checked with plain comparisons, so
// no rounding argument is needed; a box that left its inflated box (moved more than about
// skin/2), a new, removed or reordered id, or changed groups/masks force a new sweep.
//
// Layout of a pass. Box indexes carry no locality (the uniform scene's positions are random),
// so testing (index, index) pairs reads the second box at random: a cache miss per candidate
// once the bounds outgrow the cache. adopt() therefore gives the boxes that have candidates a
// spatial order (sorted by their inflated lower bound along the axis of widest spread) and
// keeps the candidates as (first position, partner position) sorted by first, then partner:
// partners overlap along that axis too, so they lie a few thousand positions apart and their
// bounds are still in the cache. A pass checks containment while it gathers the frame's
// bounds into that order (one sequential read, one scattered cache line per box), tests the
// candidates in order without a branch, sets each overlap's bit in a bit set in canonical
// order (small enough to stay in the cache), and copies the canonical candidates whose bit is
// set. The result is the same for any thread count.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/frame/box_columns.h"
#include "core/runner/buffers.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase {

/// One box's bounds in one cache line, laid out for a four-lane comparison: lanes 0-2 are the
/// axes, lane 3 holds 0 in both halves so that it passes every overlap and containment test.
struct alignas(64) BoundsRecord {
  double lo[4];
  double hi[4];
};

/// The kept candidates' memory budget: a grown sweep that finds more candidates than this a
/// box (and more than kMinKeptCandidateBudget in all) keeps none. A kept candidate costs 16
/// bytes (its canonical pair, partner position and slot), 8 more while the grown sweep's list
/// is sorted; 64 a box is 1-1.5 KB a box, several times what the plain path holds, and far above
/// what a skin that pays gives (a few a box). Without it `skin 1e300` at 4000 boxes kept all 8
/// million pairs (+515 MB).
constexpr std::size_t kMaxKeptCandidatesPerBox = 64;
/// Below this many candidates the budget does not apply (small frames of crowded boxes).
constexpr std::size_t kMinKeptCandidateBudget = std::size_t{1} << 20;

/// Most candidates kept for a frame of inBoxes boxes.
inline std::size_t keptCandidateBudget(std::size_t inBoxes) {
  return inBoxes * kMaxKeptCandidatesPerBox > kMinKeptCandidateBudget
             ? inBoxes * kMaxKeptCandidatesPerBox
             : kMinKeptCandidateBudget;
}

class SkinList {
 public:
  /// Keeps of ioPairs (pairs of ids of inBoxes, e.g. a grown sweep's candidates) those whose
  /// boxes overlap exactly in inBoxes, in their order: the frame's pairs without keeping
  /// anything.
  static void keepOverlapping(const BoxColumns& inBoxes, PairList& ioPairs);
  /// The boxes of inBoxes grown by inSkin / 2 on every side (rounded outward), kept as the
  /// reference of the next candidates and returned for the sweep that finds them (valid until
  /// the next inflate()). The last candidates and a pass's buffers are given back first: the
  /// grown sweep that follows, a frame's memory peak, runs without them.
  const BoxColumns& inflate(const BoxColumns& inBoxes, double inSkin);
  /// Keeps inCandidates (pairs of the inflated boxes, canonical order, filters honoured) as the
  /// candidates; inBoxes are the boxes given to inflate(). Throws std::length_error when there
  /// are 2^32 candidates or more (their rows are indexed in 32 bits).
  void adopt(const BoxColumns& inBoxes, const PairList& inCandidates);
  /// The same, taking the list instead of copying it: ioCandidates is left empty, and the
  /// last candidates' memory is given back before the new ones are sorted.
  void adopt(const BoxColumns& inBoxes, PairList&& ioCandidates);
  /// adopt() in steps, for a caller that spreads it over frames: startAdopt() takes the
  /// candidates, then each continueAdopt() (with the same inBoxes) does one part of the work
  /// and returns true when the candidates are kept (valid() from then on, not before).
  void startAdopt(PairList&& ioCandidates);
  /// The parts of adopt() that continueAdopt() does one a call.
  static constexpr int kAdoptParts = 4;
  bool continueAdopt(const BoxColumns& inBoxes);
  /// True when every box of inBoxes lies inside its inflated box (same ids, groups and masks in
  /// the same order), and then the frame's bounds are gathered for collectGathered(). One read
  /// of the frame, so that the engine can know before planning whether the candidates answer
  /// the frame; when they do not, the caller sweeps (inflate, sweep, adopt) instead.
  bool gather(const BoxColumns& inBoxes);
  /// After gather() returned true for this frame: the candidates that overlap exactly in the
  /// gathered bounds, in canonical order, into outPairs.
  void collectGathered(PairList& outPairs);
  /// The containment test of gather() alone, without gathering.
  bool covers(const BoxColumns& inBoxes) const;
  /// The inflated boxes of the last inflate() (ids, groups and masks included).
  const BoxColumns& reference() const { return reference_; }
  /// True while candidates are kept (after adopt(), until clear() or the next inflate()).
  bool valid() const { return valid_; }
  /// Number of candidate pairs kept.
  std::size_t candidates() const { return canonical_pairs_.size(); }
  /// True when inOther keeps the same candidates laid out the same way (spatial order, runs,
  /// partners and slots): tests check with it that the thread count changes nothing.
  bool sameCandidates(const SkinList& inOther) const;
  /// Forgets the candidates (the next frame sweeps).
  void clear() { valid_ = frame_gathered_ = false; }
  /// Forgets the candidates and gives back their memory and a pass's, keeping the grown boxes'
  /// columns for the next inflate() to reuse.
  void releaseCandidates();

  /// Bytes held (capacities), by part: for the memory experiment (bench/exp_memory.cpp).
  struct MemoryUse {
    std::size_t reference = 0;   ///< the grown boxes of the last sweep
    std::size_t candidates = 0;  ///< the kept candidates: pairs, spatial order, runs
    std::size_t pass = 0;        ///< a pass's gathered bounds and verdict bits
    std::size_t scratch = 0;     ///< adopt()'s working lists (held while it runs)
  };
  MemoryUse memoryUse() const;

 private:
  bool sameCounts(const BoxColumns& inBoxes) const;
  bool sameIdsAndFilters(const BoxColumns& inBoxes, std::size_t inBegin, std::size_t inEnd) const;
  bool holdsEveryCandidate() const;
  std::size_t scratchBytes() const;
  void keepBoxIndexes(const BoxColumns& inBoxes);
  void keepSpatialOrder();
  void keepSpatialCandidates();
  void sortRunsByPartner();
  bool gatherInside(const BoxColumns& inBoxes);
  void testSpatialCandidates();
  void copyHits(PairList& outPairs);
  std::size_t verdictWords() const { return (canonical_pairs_.size() + 63) / 64; }

  BoxColumns reference_;  // the inflated boxes of the last sweep (ids, groups, masks included)
  // The spatial order: positions 0..m-1 for the m boxes that have candidates; the others all
  // have position m, which a pass turns into a scratch record per thread that no candidate
  // reads.
  Buffer<uint32_t> position_of_;  // box index -> position
  uint32_t spatial_count_ = 0;    // m
  // The candidates by (first position, partner position), first < partner: those of first
  // position p are [run_begin_[p], run_begin_[p + 1]) (a first position is not kept per
  // candidate: 4 bytes a candidate less).
  Buffer<uint32_t> run_begin_;
  Buffer<uint32_t> partner_positions_;
  Buffer<uint32_t> canonical_slots_;  // the candidate's index in canonical_pairs_
  PairList canonical_pairs_;          // the candidates, as adopted (taken, not copied)
  // Per pass: the frame's bounds by position, and a verdict bit per canonical candidate, one
  // row of verdictWords() words per thread (bit k of the row: candidate k overlaps).
  Buffer<BoundsRecord> gathered_;
  // adopt()'s working lists, a few words a box and one a candidate (the candidates' own arrays
  // hold their box indexes while they are sorted), given back when adopt() is done; buffers,
  // so that sizing them zeroes nothing.
  struct AdoptScratch {
    Buffer<uint8_t> has_candidates;  // by box index
    Buffer<uint32_t> members;        // boxes with candidates
    Buffer<uint32_t> keys;           // their sort keys
    Buffer<uint32_t> order;
    Buffer<uint32_t> fill;  // by first position: where its next candidate goes
  } scratch_;
  std::size_t adopt_scratch_bytes_ = 0;  // what the last adopt()'s working lists held
  Buffer<uint64_t> verdicts_;
  int verdict_rows_ = 1;  // the threads of the last test, each with its row
  int adopt_step_ = 0;    // the next part of adopt() that continueAdopt() does
  bool valid_ = false;
  bool frame_gathered_ = false;  // gather() succeeded and collectGathered() has not run since
};

}  // namespace sap_broadphase
