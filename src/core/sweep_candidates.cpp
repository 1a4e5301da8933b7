// Candidate generation on the primary axis: Algorithm 1 (lines 5-14) and Algorithm 3.
#include <omp.h>

#include <algorithm>

#include "core/buffers.h"
#include "core/sweep.h"

namespace sap_broadphase {
namespace {

// Sweeps order[inBegin, inEnd) of the primary axis from the active set ioActive and the rank
// counter inLowsBefore, writing L and U (Algorithm 1, lines 6-14 without rank assignment).
void sweepCandidateSlice(const uint32_t* inOrder, uint32_t inObjects, std::size_t inBegin,
                         std::size_t inEnd, uint32_t inLowsBefore, SuccTree& ioActive,
                         RankRange* ioRanges) {
  uint32_t lows_seen = inLowsBefore;
  // Ranks are handed out in sweep order, so an insert never lowers the minimum: it only
  // changes when the minimum itself leaves, and is cached in between.
  uint32_t minimum = ioActive.min();
  for (std::size_t k = inBegin; k < inEnd; ++k) {
    const uint32_t endpoint = inOrder[k];
    if (endpoint < inObjects) {
      RankRange& range = ioRanges[endpoint];
      if (minimum == SuccTree::kNone) minimum = range.rank;
      range.low = minimum;
      ioActive.insert(range.rank);
      ++lows_seen;
    } else {
      RankRange& range = ioRanges[endpoint - inObjects];
      range.high = lows_seen;
      ioActive.erase(range.rank);
      if (range.rank == minimum) minimum = ioActive.next(range.rank);
    }
  }
}

}  // namespace

void computeCandidatesSequential(const uint32_t* inPrimaryOrder, uint32_t inObjects,
                                 SuccTree& ioActive, CandidateRanges& outRanges) {
  resizeDiscarding(outRanges.of_object, inObjects);
  resizeDiscarding(outRanges.object_of_rank, inObjects);
  uint32_t next_rank = 0;
  for (std::size_t k = 0; k < 2 * std::size_t{inObjects}; ++k) {
    const uint32_t endpoint = inPrimaryOrder[k];
    if (endpoint < inObjects) {
      outRanges.of_object[endpoint].rank = next_rank;
      outRanges.object_of_rank[next_rank++] = endpoint;
    }
  }
  ioActive.resize(inObjects);
  sweepCandidateSlice(inPrimaryOrder, inObjects, 0, 2 * std::size_t{inObjects}, 0, ioActive,
                      outRanges.of_object.data());
}

void computeCandidatesParallel(const uint32_t* inPrimaryOrder, uint32_t inObjects, int inThreads,
                               SweepWorkspace& ioWork, CandidateRanges& outRanges) {
  const int slices = std::max(1, inThreads);
  const std::size_t endpoints = 2 * std::size_t{inObjects};
  const std::size_t words = (std::size_t{inObjects} + 63) / 64;
  resizeDiscarding(outRanges.of_object, inObjects);
  resizeDiscarding(outRanges.object_of_rank, inObjects);
  resizeDiscarding(ioWork.slice_objects, words * slices);
  ioWork.slice_start.resize(slices);
  ioWork.lows_before.assign(slices + 1, 0);
  RankRange* ranges = outRanges.of_object.data();
  uint32_t* object_of_rank = outRanges.object_of_rank.data();
#pragma omp parallel num_threads(slices)
  {
    const int slice = omp_get_thread_num();
    const std::size_t begin = endpoints * slice / slices;
    const std::size_t end = endpoints * (slice + 1) / slices;
    // Lines 4-7 and 12-14 in one pass: count the slice's lows, and build its set of objects
    // with one endpoint inside (both inside: flipped twice, absent). The paper's set holds
    // ranks, which for a high whose low lies in another slice are known only once every
    // slice has handed out its ranks, and each costs a random read then; an object's index
    // is its endpoint's, so the whole set is built before any rank exists.
    uint64_t* crossing = &ioWork.slice_objects[words * slice];
    std::fill(crossing, crossing + words, uint64_t{0});
    uint32_t lows = 0;
    for (std::size_t k = begin; k < end; ++k) {
      const uint32_t endpoint = inPrimaryOrder[k];
      const uint32_t is_low = endpoint < inObjects;
      const uint32_t object = endpoint - (is_low ? 0u : inObjects);
      crossing[object >> 6] ^= uint64_t{1} << (object & 63);
      lows += is_low;
    }
    ioWork.lows_before[slice + 1] = lows;
#pragma omp barrier
#pragma omp single
    for (int s = 0; s < slices; ++s) ioWork.lows_before[s + 1] += ioWork.lows_before[s];
    // Lines 8-11: ranks (the implicit barrier of `single` published the rank bases).
    uint32_t next_rank = ioWork.lows_before[slice];
    for (std::size_t k = begin; k < end; ++k) {
      const uint32_t endpoint = inPrimaryOrder[k];
      if (endpoint < inObjects) {
        ranges[endpoint].rank = next_rank;
        object_of_rank[next_rank++] = endpoint;
      }
    }
#pragma omp barrier
    // Line 15: the objects active at the start of the slice, those with an odd number of
    // endpoints before it, are the ⊕ of all earlier slices' sets; their ranks seed the sweep.
    SuccTree& active = ioWork.slice_start[slice];
    if (active.size() != inObjects) active.resize(inObjects);
    for (std::size_t word = 0; slice > 0 && word < words; ++word) {
      uint64_t bits = 0;
      for (int earlier = 0; earlier < slice; ++earlier)
        bits ^= ioWork.slice_objects[words * earlier + word];
      while (bits) {
        const uint32_t object = static_cast<uint32_t>(word * 64 + __builtin_ctzll(bits));
        active.insert(ranges[object].rank);
        bits &= bits - 1;
      }
    }
    // Lines 16-23.
    sweepCandidateSlice(inPrimaryOrder, inObjects, begin, end, ioWork.lows_before[slice], active,
                        ranges);
    active.clear();  // leave the tree empty for the next frame
  }
}

}  // namespace sap_broadphase
