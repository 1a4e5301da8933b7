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
  resizeDiscarding(outRanges.of_object, inObjects);
  resizeDiscarding(outRanges.object_of_rank, inObjects);
  ioWork.partition_local.resize(slices);
  ioWork.partition_start.resize(slices);
  ioWork.lows_before.assign(slices + 1, 0);
  RankRange* ranges = outRanges.of_object.data();
  uint32_t* object_of_rank = outRanges.object_of_rank.data();
#pragma omp parallel num_threads(slices)
  {
    const int slice = omp_get_thread_num();
    const std::size_t begin = endpoints * slice / slices;
    const std::size_t end = endpoints * (slice + 1) / slices;
    // Lines 4-7: count the lows of each slice, then an exclusive prefix sum gives rank bases.
    uint32_t lows = 0;
    for (std::size_t k = begin; k < end; ++k) lows += inPrimaryOrder[k] < inObjects;
    ioWork.lows_before[slice + 1] = lows;
#pragma omp barrier
#pragma omp single
    for (int s = 0; s < slices; ++s) ioWork.lows_before[s + 1] += ioWork.lows_before[s];
    // Lines 8-11: ranks. Lines 12-14 build each slice's own tree, the ranks with one endpoint
    // inside the slice, by flipping leaf bits (both endpoints inside: flipped twice, absent),
    // then its summaries in one pass: a low's rank is known right here, a high's once every
    // slice has handed out its ranks.
    SuccTree& local = ioWork.partition_local[slice];
    if (local.size() != inObjects) local.resize(inObjects);
    uint32_t next_rank = ioWork.lows_before[slice];
    for (std::size_t k = begin; k < end; ++k) {
      const uint32_t endpoint = inPrimaryOrder[k];
      if (endpoint < inObjects) {
        ranges[endpoint].rank = next_rank;
        object_of_rank[next_rank] = endpoint;
        local.flipLeaf(next_rank++);
      }
    }
#pragma omp barrier
    for (std::size_t k = begin; k < end; ++k) {
      const uint32_t endpoint = inPrimaryOrder[k];
      if (endpoint >= inObjects) local.flipLeaf(ranges[endpoint - inObjects].rank);
    }
    local.rebuildSummaries();
#pragma omp barrier
    // Line 15: the active set at the start of the slice is the ⊕ of all earlier slices' trees.
    SuccTree& active = ioWork.partition_start[slice];
    if (active.size() != inObjects)
      active.resize(inObjects);
    else
      active.clear();
    for (int earlier = 0; earlier < slice; ++earlier)
      active.symmetricDifference(ioWork.partition_local[earlier]);
    // Lines 16-23.
    sweepCandidateSlice(inPrimaryOrder, inObjects, begin, end, ioWork.lows_before[slice], active,
                        ranges);
#pragma omp barrier
    local.clear();  // leave both trees empty for the next frame
    active.clear();
  }
}

}  // namespace sap_broadphase
