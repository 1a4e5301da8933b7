#include "sap_broadphase/core/sweep.h"

#include <omp.h>

#include <algorithm>

namespace sap_broadphase {
namespace {

// The exact closed-interval test on all three axes, on float64 values.
inline bool overlaps(const RankedBox& inA, const RankedBox& inB) {
  return inA.lo[0] <= inB.hi[0] && inB.lo[0] <= inA.hi[0] && inA.lo[1] <= inB.hi[1] &&
         inB.lo[1] <= inA.hi[1] && inA.lo[2] <= inB.hi[2] && inB.lo[2] <= inA.hi[2];
}

// The keys-only test: outward-rounded float32 keys (a superset of the exact pairs).
inline bool overlaps(const RankedKeys& inA, const RankedKeys& inB) {
  return inA.lo[0] <= inB.hi[0] && inB.lo[0] <= inA.hi[0] && inA.lo[1] <= inB.hi[1] &&
         inB.lo[1] <= inA.hi[1] && inA.lo[2] <= inB.hi[2] && inB.lo[2] <= inA.hi[2];
}

inline bool filtersAllow(const RankedFilter& inA, const RankedFilter& inB) {
  return (inA.group & inB.mask) != 0 && (inB.group & inA.mask) != 0;
}

// Tests object inObject (rank inObjectRank) against the active ranks of one slab's tree in
// [inBegin, inEnd) (local ranks; add inRankOffset for global ranks).
template <typename Ranked>
inline void testCandidates(const PairingInput& inInput, const Ranked* inRanked,
                           const SuccTree& inActive, int inSlab, uint32_t inRankOffset,
                           uint32_t inBegin, uint32_t inEnd, uint32_t inObject,
                           uint32_t inObjectRank, PairList& outPairs) {
  const Ranked& box = inRanked[inObjectRank];
  const RankedFilter* filters = inInput.filters;
  const RankedSlabs* slabs = inInput.slabs;
  const uint32_t* object_of_rank = inInput.object_of_rank;
  inActive.forEachInRange(inBegin, inEnd, [&](uint32_t inLocalRank) {
    const uint32_t other_rank = inLocalRank + inRankOffset;
    // A pair sharing several slabs is reported only in the slab of the larger low end.
    if (slabs && inSlab != std::max(slabs[inObjectRank].first, slabs[other_rank].first)) return;
    if (!overlaps(box, inRanked[other_rank])) return;
    if (filters && !filtersAllow(filters[inObjectRank], filters[other_rank])) return;
    outPairs.push_back(makeIdPair(inInput.ids[inObject], inInput.ids[object_of_rank[other_rank]]));
  });
}

// Algorithm 4 for the ranks [inRankBegin, inRankEnd), with one active tree per slab.
template <typename Ranked>
void pairPartition(const PairingInput& inInput, const Ranked* inRanked,
                   const SecondaryEndpoint* inStream, std::size_t inEndpoints, uint32_t inRankBegin,
                   uint32_t inRankEnd, SuccTree* ioActive, PairList& outPairs) {
  const SecondaryEndpoint* stream = inStream;
  for (std::size_t k = 0; k < inEndpoints; ++k) {
    const SecondaryEndpoint& endpoint = stream[k];
    const uint32_t rank = endpoint.rank_and_kind & ~SecondaryEndpoint::kHighBit;
    const bool mine = rank >= inRankBegin && rank < inRankEnd;
    if (endpoint.rank_and_kind & SecondaryEndpoint::kHighBit) {
      if (mine)
        for (int slab = endpoint.slabs.first; slab <= endpoint.slabs.last; ++slab)
          ioActive[slab].erase(rank - inRankBegin);
      continue;
    }
    // Algorithm 4, lines 10-12: clip the candidate range to this partition's ranks.
    if (endpoint.low < inRankEnd && inRankBegin < endpoint.high) {
      const uint32_t begin = std::max(endpoint.low, inRankBegin) - inRankBegin;
      const uint32_t end = std::min(endpoint.high, inRankEnd) - inRankBegin;
      const uint32_t object = inInput.object_of_rank[rank];
      for (int slab = endpoint.slabs.first; slab <= endpoint.slabs.last; ++slab)
        testCandidates(inInput, inRanked, ioActive[slab], slab, inRankBegin, begin, end, object,
                       rank, outPairs);
    }
    if (mine)
      for (int slab = endpoint.slabs.first; slab <= endpoint.slabs.last; ++slab)
        ioActive[slab].insert(rank - inRankBegin);
  }
}

void pairRankRange(const PairingInput& inInput, const SecondaryEndpoint* inStream,
                   std::size_t inEndpoints, uint32_t inRankBegin, uint32_t inRankEnd,
                   SuccTree* ioActive, PairList& outPairs) {
  if (inInput.boxes)
    pairPartition(inInput, inInput.boxes, inStream, inEndpoints, inRankBegin, inRankEnd, ioActive,
                  outPairs);
  else
    pairPartition(inInput, inInput.keys, inStream, inEndpoints, inRankBegin, inRankEnd, ioActive,
                  outPairs);
}

// The rank partitions an endpoint matters to: its own (insert, erase) and, for a low endpoint,
// every partition its candidate range [L, U) reaches (which includes its own: L <= R < U).
inline void partitionsOf(const SecondaryEndpoint& inEndpoint, uint32_t inPartitionSize,
                         uint32_t& outFirst, uint32_t& outLast) {
  const uint32_t rank = inEndpoint.rank_and_kind & ~SecondaryEndpoint::kHighBit;
  if (inEndpoint.rank_and_kind & SecondaryEndpoint::kHighBit) {
    outFirst = outLast = rank / inPartitionSize;
  } else {
    outFirst = std::min(inEndpoint.low, rank) / inPartitionSize;
    outLast = (std::max(inEndpoint.high, rank + 1) - 1) / inPartitionSize;
  }
}

// Copies each endpoint of the stream to the streams of the partitions it matters to, keeping
// sweep order within each (threads take contiguous slices; counts, then placement).
void scatterToPartitions(const PairingInput& inInput, int inThreads, uint32_t inPartitionSize,
                         uint32_t inPartitions, SweepWorkspace& ioWork) {
  const std::size_t endpoints = 2 * std::size_t{inInput.objects};
  const SecondaryEndpoint* stream = inInput.stream;
  std::vector<std::size_t>& counts = ioWork.scatter_counts;
  counts.assign(std::size_t(inThreads) * inPartitions, 0);
  ioWork.partition_offsets.assign(inPartitions + 1, 0);
#pragma omp parallel num_threads(inThreads)
  {
    const int thread = omp_get_thread_num();
    const int team = omp_get_num_threads();
    const std::size_t begin = endpoints * thread / team;
    const std::size_t end = endpoints * (thread + 1) / team;
    std::size_t* my_counts = &counts[std::size_t(thread) * inPartitions];
    uint32_t first = 0, last = 0;
    for (std::size_t k = begin; k < end; ++k) {
      partitionsOf(stream[k], inPartitionSize, first, last);
      for (uint32_t p = first; p <= last; ++p) ++my_counts[p];
    }
#pragma omp barrier
#pragma omp single
    {
      std::size_t offset = 0;
      for (uint32_t p = 0; p < inPartitions; ++p) {
        ioWork.partition_offsets[p] = offset;
        for (int t = 0; t < team; ++t) {
          std::size_t& slot = counts[std::size_t(t) * inPartitions + p];
          const std::size_t size = slot;
          slot = offset;
          offset += size;
        }
      }
      ioWork.partition_offsets[inPartitions] = offset;
      ioWork.partition_streams.resize(offset);
    }
    SecondaryEndpoint* out = ioWork.partition_streams.data();
    for (std::size_t k = begin; k < end; ++k) {
      partitionsOf(stream[k], inPartitionSize, first, last);
      for (uint32_t p = first; p <= last; ++p) out[my_counts[p]++] = stream[k];
    }
  }
}

// Makes trees [inFirst, inFirst + inCount) of ioTrees empty trees over inSize ranks.
void prepareTrees(std::vector<SuccTree>& ioTrees, std::size_t inFirst, int inCount,
                  uint32_t inSize) {
  for (int t = 0; t < inCount; ++t) {
    SuccTree& tree = ioTrees[inFirst + t];
    if (tree.size() != inSize) tree.resize(inSize);  // same size: left empty by the last sweep
  }
}

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
  outRanges.of_object.resize(inObjects);
  outRanges.object_of_rank.resize(inObjects);
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
  outRanges.of_object.resize(inObjects);
  outRanges.object_of_rank.resize(inObjects);
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
    // Lines 8-11: ranks.
    uint32_t next_rank = ioWork.lows_before[slice];
    for (std::size_t k = begin; k < end; ++k) {
      const uint32_t endpoint = inPrimaryOrder[k];
      if (endpoint < inObjects) {
        ranges[endpoint].rank = next_rank;
        object_of_rank[next_rank++] = endpoint;
      }
    }
    // Lines 12-14: each slice's own tree keeps the ranks with one endpoint inside the slice.
    SuccTree& local = ioWork.partition_local[slice];
    if (local.size() != inObjects) local.resize(inObjects);
#pragma omp barrier
    for (std::size_t k = begin; k < end; ++k) {
      const uint32_t endpoint = inPrimaryOrder[k];
      local.toggle(ranges[endpoint < inObjects ? endpoint : endpoint - inObjects].rank);
    }
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

void buildSecondaryStream(const uint32_t* inSecondaryOrder, uint32_t inObjects,
                          const CandidateRanges& inRanges, const RankedSlabs* inSlabs,
                          int inThreads, std::vector<SecondaryEndpoint>& outStream) {
  const std::size_t endpoints = 2 * std::size_t{inObjects};
  outStream.resize(endpoints);
  const RankRange* ranges = inRanges.of_object.data();
#pragma omp parallel for num_threads(inThreads) schedule(static)
  for (std::size_t k = 0; k < endpoints; ++k) {
    const uint32_t endpoint = inSecondaryOrder[k];
    const bool is_high = endpoint >= inObjects;
    const RankRange& range = ranges[is_high ? endpoint - inObjects : endpoint];
    SecondaryEndpoint& out = outStream[k];
    out.rank_and_kind = range.rank | (is_high ? SecondaryEndpoint::kHighBit : 0u);
    out.low = range.low;
    out.high = range.high;
    out.slabs = inSlabs ? inSlabs[range.rank] : RankedSlabs{0, 0};
  }
}

void pairSequential(const PairingInput& inInput, SweepWorkspace& ioWork, PairList& outPairs) {
  ioWork.pairing.resize(std::max<std::size_t>(ioWork.pairing.size(), inInput.slab_count));
  prepareTrees(ioWork.pairing, 0, inInput.slab_count, inInput.objects);
  pairRankRange(inInput, inInput.stream, 2 * std::size_t{inInput.objects}, 0, inInput.objects,
                ioWork.pairing.data(), outPairs);
}

void pairParallel(const PairingInput& inInput, int inThreads, SweepWorkspace& ioWork,
                  std::vector<PairList>& outPairsPerThread) {
  const int threads = std::max(1, inThreads);
  const uint32_t n = inInput.objects;
  const uint32_t wanted =
      std::max<uint32_t>(threads, (n + kPairingPartitionRanks - 1) / kPairingPartitionRanks);
  const uint32_t partition_size = std::max<uint32_t>(1, (n + wanted - 1) / wanted);  // Δ
  const uint32_t partitions = (n + partition_size - 1) / partition_size;
  scatterToPartitions(inInput, threads, partition_size, partitions, ioWork);
  const int slab_count = inInput.slab_count;
  ioWork.pairing.resize(
      std::max<std::size_t>(ioWork.pairing.size(), std::size_t(threads) * slab_count));
  outPairsPerThread.resize(threads);
#pragma omp parallel num_threads(threads)
  {
    const int thread = omp_get_thread_num();
    SuccTree* trees = &ioWork.pairing[std::size_t(thread) * slab_count];
    prepareTrees(ioWork.pairing, std::size_t(thread) * slab_count, slab_count, partition_size);
    PairList& pairs = outPairsPerThread[thread];
    pairs.clear();
#pragma omp for schedule(dynamic, 1)
    for (uint32_t p = 0; p < partitions; ++p) {
      const uint32_t rank_begin = p * partition_size;
      const uint32_t rank_end = std::min(n, rank_begin + partition_size);
      const std::size_t begin = ioWork.partition_offsets[p];
      const std::size_t end = ioWork.partition_offsets[p + 1];
      pairRankRange(inInput, ioWork.partition_streams.data() + begin, end - begin, rank_begin,
                    rank_end, trees, pairs);
    }
  }
}

}  // namespace sap_broadphase
