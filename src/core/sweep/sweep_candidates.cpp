// Candidate generation on the primary axis: Algorithm 1 (lines 5-14) and Algorithm 3.

#include <algorithm>

#include "core/assert.h"
#include "core/runner/buffers.h"
#include "core/runner/work_units.h"
#include "core/sweep/sweep.h"
#include "core/tuning.h"

namespace sap_broadphase {
namespace {

// The records are read and written in primary order, at random: fetched ahead.
constexpr std::size_t kRecordPrefetchAhead = tuning::kEndpointPrefetchAhead;

inline bool containsBit(const uint64_t* inBits, uint32_t inIndex) {
  return (inBits[inIndex >> 6] >> (inIndex & 63)) & 1u;
}

// Sweeps order[inBegin, inEnd) of the primary axis from the active set ioActive and the rank
// counter inLowsBefore (Algorithm 1, lines 6-14), handing out ranks as it goes: a low's rank
// is the count of lows before it. The rank of a box whose low lies in this slice and whose
// high lies beyond it (inCrossing, when given) was written before the sweep, for the slices
// that meet its high, and is left alone here.
void sweepCandidateSlice(const uint32_t* inOrder, uint32_t inObjects, std::size_t inBegin,
                         std::size_t inEnd, uint32_t inLowsBefore, const uint64_t* inCrossing,
                         SuccTree& ioActive, CandidateRanges& ioRanges) {
  RankRange* ranges = ioRanges.of_object.data();
  uint32_t* object_of_rank = ioRanges.object_of_rank.data();
  uint32_t lows_seen = inLowsBefore;
  // Ranks are handed out in sweep order, so an insert never lowers the minimum: it only
  // changes when the minimum itself leaves, and is cached in between.
  uint32_t minimum = ioActive.min();
  for (std::size_t k = inBegin; k < inEnd; ++k) {
    if (k + kRecordPrefetchAhead < inEnd) {
      const uint32_t ahead = inOrder[k + kRecordPrefetchAhead];
      __builtin_prefetch(&ranges[ahead - (ahead < inObjects ? 0u : inObjects)], 1);
    }
    const uint32_t endpoint = inOrder[k];
    if (endpoint < inObjects) {
      RankRange& range = ranges[endpoint];
      const uint32_t rank = lows_seen++;
      if (!inCrossing || !containsBit(inCrossing, endpoint)) range.rank = rank;
      object_of_rank[rank] = endpoint;
      if (minimum == SuccTree::kNone) minimum = rank;
      SAP_ASSERT(minimum <= rank, "a candidate range starts after its own rank (L > R)");
      range.low = minimum;
      ioActive.insert(rank);
    } else {
      RankRange& range = ranges[endpoint - inObjects];
      const uint32_t rank = range.rank;
      range.high = lows_seen;
      // (L, written at the low, may belong to another slice's thread: checked after the sweep.)
      SAP_ASSERT(rank < range.high, "a candidate range ends before its own rank (R >= U)");
      SAP_ASSERT(ioActive.contains(rank), "a high endpoint whose box is not active");
      ioActive.erase(rank);
      if (rank == minimum) minimum = ioActive.next(rank);
    }
  }
}

// Every object's candidate range holds its rank, L <= R < U <= n, and R^- inverts R: what
// pairing relies on to find each pair once (a scan of the frame, asserted builds only).
[[maybe_unused]] bool rangesAreConsistent(const CandidateRanges& inRanges, uint32_t inObjects) {
  for (uint32_t object = 0; object < inObjects; ++object) {
    const RankRange& range = inRanges.of_object[object];
    if (!(range.low <= range.rank && range.rank < range.high && range.high <= inObjects))
      return false;
    if (inRanges.object_of_rank[range.rank] != object) return false;
  }
  return true;
}

// Slice inSlice of inSlices of the primary order: [outBegin, outEnd).
inline void sliceBounds(uint32_t inObjects, int inSlice, int inSlices, std::size_t& outBegin,
                        std::size_t& outEnd) {
  const std::size_t endpoints = 2 * std::size_t{inObjects};
  outBegin = endpoints * inSlice / inSlices;
  outEnd = endpoints * (inSlice + 1) / inSlices;
}

// Algorithm 3, lines 4-7 and 12-14 in one pass: counts the slice's lows, and builds its set of
// objects with one endpoint inside (both inside: flipped twice, absent). The paper's set holds
// ranks, which for a high whose low lies in another slice are known only once every slice has
// handed out its ranks, and each costs a random read then; an object's index is its
// endpoint's, so the whole set is built before any rank exists.
void countAndCollectCrossing(const uint32_t* inOrder, uint32_t inObjects, int inSlice, int inSlices,
                             SweepWorkspace& ioWork) {
  std::size_t begin = 0, end = 0;
  sliceBounds(inObjects, inSlice, inSlices, begin, end);
  const std::size_t words = (std::size_t{inObjects} + 63) / 64;
  uint64_t* crossing = ioWork.slice_objects.data() + words * inSlice;
  std::fill(crossing, crossing + words, uint64_t{0});
  uint32_t lows = 0;
  for (std::size_t k = begin; k < end; ++k) {
    const uint32_t endpoint = inOrder[k];
    const uint32_t is_low = endpoint < inObjects;
    const uint32_t object = endpoint - (is_low ? 0u : inObjects);
    crossing[object >> 6] ^= uint64_t{1} << (object & 63);
    lows += is_low;
  }
  ioWork.lows_before[inSlice + 1] = lows;
}

// Algorithm 3, lines 8-11, for the boxes that leave the slice (low inside, high beyond: in the
// set) only, which later slices need before their sweeps; the sweep ranks the others. A box's
// record is written by the thread that reads it next (this one, in its sweep), except for
// these few: two threads writing the same records would pass their cache lines between the
// cores. Lows and highs alternate at random: no branch on the kind, only on the rare leaving
// box.
void rankLeavingBoxes(const uint32_t* inOrder, uint32_t inObjects, int inSlice, int inSlices,
                      const SweepWorkspace& inWork, RankRange* ioRanges) {
  std::size_t begin = 0, end = 0;
  sliceBounds(inObjects, inSlice, inSlices, begin, end);
  const std::size_t words = (std::size_t{inObjects} + 63) / 64;
  const uint64_t* crossing = inWork.slice_objects.data() + words * inSlice;
  uint32_t next_rank = inWork.lows_before[inSlice];
  for (std::size_t k = begin; k < end; ++k) {
    const uint32_t endpoint = inOrder[k];
    const uint32_t is_low = endpoint < inObjects;
    const uint32_t object = endpoint - (is_low ? 0u : inObjects);
    if (is_low & containsBit(crossing, object)) ioRanges[object].rank = next_rank;
    next_rank += is_low;
  }
}

// Algorithm 3, line 15: the objects active at the start of slice inSlice, those with an odd
// number of endpoints before it, are the ⊕ of all earlier slices' sets; their ranks (written
// by rankLeavingBoxes) seed the slice's active set.
void seedActiveFromEarlierSlices(uint32_t inObjects, int inSlice, const SweepWorkspace& inWork,
                                 const RankRange* inRanges, SuccTree& outActive) {
  if (outActive.size() != inObjects) outActive.resize(inObjects);
  const std::size_t words = (std::size_t{inObjects} + 63) / 64;
  for (std::size_t word = 0; inSlice > 0 && word < words; ++word) {
    uint64_t bits = 0;
    for (int earlier = 0; earlier < inSlice; ++earlier)
      bits ^= inWork.slice_objects[words * earlier + word];
    while (bits) {
      const uint32_t object = static_cast<uint32_t>(word * 64 + __builtin_ctzll(bits));
      SAP_ASSERT(inRanges[object].rank < inWork.lows_before[inSlice],
                 "a box active at a slice's start was ranked in a later slice");
      outActive.insert(inRanges[object].rank);
      bits &= bits - 1;
    }
  }
}

}  // namespace

void computeCandidatesSequential(const uint32_t* inPrimaryOrder, uint32_t inObjects,
                                 SuccTree& ioActive, CandidateRanges& outRanges) {
  resizeDiscarding(outRanges.of_object, inObjects);
  resizeDiscarding(outRanges.object_of_rank, inObjects);
  ioActive.resize(inObjects);
  sweepCandidateSlice(inPrimaryOrder, inObjects, 0, 2 * std::size_t{inObjects}, 0, nullptr,
                      ioActive, outRanges);
  SAP_ASSERT(ioActive.empty(), "a box still active after the whole primary order");
  SAP_ASSERT(rangesAreConsistent(outRanges, inObjects), "candidate ranges not L <= R < U <= n");
}

void computeCandidatesParallel(const uint32_t* inPrimaryOrder, uint32_t inObjects,
                               SweepWorkspace& ioWork, CandidateRanges& outRanges) {
  // More slices than threads, each phase's slices claimed dynamically (work_units.h): a
  // descheduled thread's slices are swept by the others.
  const int slices = unitsForThreads(passThreads());
  const std::size_t words = (std::size_t{inObjects} + 63) / 64;
  resizeDiscarding(outRanges.of_object, inObjects);
  resizeDiscarding(outRanges.object_of_rank, inObjects);
  resizeDiscarding(ioWork.slice_objects, words * slices);
  ioWork.slice_start.resize(slices);
  ioWork.lows_before.assign(slices + 1, 0);
  RankRange* ranges = outRanges.of_object.data();
  runUnits(slices, [&](std::size_t inSlice) {
    countAndCollectCrossing(inPrimaryOrder, inObjects, static_cast<int>(inSlice), slices, ioWork);
  });
  for (int s = 0; s < slices; ++s) ioWork.lows_before[s + 1] += ioWork.lows_before[s];
  runUnits(slices, [&](std::size_t inSlice) {
    rankLeavingBoxes(inPrimaryOrder, inObjects, static_cast<int>(inSlice), slices, ioWork, ranges);
  });
  runUnits(slices, [&](std::size_t inSlice) {
    const int slice = static_cast<int>(inSlice);
    SuccTree& active = ioWork.slice_start[slice];
    seedActiveFromEarlierSlices(inObjects, slice, ioWork, ranges, active);
    // Lines 16-23, with the ranks of the boxes that start in the slice.
    std::size_t begin = 0, end = 0;
    sliceBounds(inObjects, slice, slices, begin, end);
    sweepCandidateSlice(inPrimaryOrder, inObjects, begin, end, ioWork.lows_before[slice],
                        ioWork.slice_objects.data() + words * slice, active, outRanges);
    active.clear();  // leave the tree empty for the next frame
  });

  SAP_ASSERT(ioWork.lows_before[slices] == inObjects, "the slices' lows do not add up to n");
  SAP_ASSERT(rangesAreConsistent(outRanges, inObjects), "candidate ranges not L <= R < U <= n");
}

}  // namespace sap_broadphase
