// Pairing on the secondary axis: Algorithm 1 (lines 15-23) and Algorithm 4, with one active
// list per third-axis slab (slab_grid.h).

#include <algorithm>
#include <numeric>

#include "core/assert.h"
#include "core/runner/buffers.h"
#include "core/runner/phase_timer.h"
#include "core/runner/work_units.h"
#include "core/sweep/sweep.h"
#include "core/tuning.h"

namespace sap_broadphase {
namespace {

// Entries of a partition's endpoint list, one 64-bit word each:
//   bits 0-30  the box's primary rank
//   bit 63     set for a high endpoint
//   bits 31-46 (low endpoints) start of the candidate range, local to the partition
//   bits 47-62 (low endpoints) end of the candidate range, local to the partition
constexpr uint64_t kEntryHighBit = uint64_t{1} << 63;
constexpr uint32_t kRankMask = 0x7FFFFFFFu;
constexpr uint32_t kLocalRankMask = 0xFFFFu;
static_assert(kMaxBoxes - 1 <= kRankMask, "every rank must fit in an entry's 31 rank bits");
static_assert(tuning::kPairingPartitionRanks <= kLocalRankMask,
              "a partition's local candidate range (ends included) must fit in 16 bits");

inline uint64_t lowEntry(uint32_t inRank, uint32_t inLocalBegin, uint32_t inLocalEnd) {
  SAP_ASSERT(inRank <= kRankMask && inLocalBegin <= inLocalEnd && inLocalEnd <= kLocalRankMask,
             "a pairing entry's rank or local candidate range does not fit its bits");
  return inRank | (uint64_t{inLocalBegin} << 31) | (uint64_t{inLocalEnd} << 47);
}
inline uint64_t highEntry(uint32_t inRank) {
  return inRank | kEntryHighBit;
}

// The secondary-axis order with all that pairing reads about each endpoint's box, two 64-bit
// words an endpoint, in sweep order: word 0 = rank | kind << 31 | L << 32, word 1 = U. Built
// where a pass reads every endpoint more than once (the one-thread sweep of the whole order,
// a scatter that counts before it places), so that those passes read it in order instead of
// looking boxes up at random. It fits in the sort's buffer, which is free by then.
namespace secondary_stream {
constexpr uint32_t kHighBit = 0x80000000u;
inline uint32_t rankAndKind(const uint64_t* inStream, std::size_t inEndpoint) {
  return static_cast<uint32_t>(inStream[2 * inEndpoint]);
}
inline uint32_t low(const uint64_t* inStream, std::size_t inEndpoint) {
  return static_cast<uint32_t>(inStream[2 * inEndpoint] >> 32);
}
inline uint32_t high(const uint64_t* inStream, std::size_t inEndpoint) {
  return static_cast<uint32_t>(inStream[2 * inEndpoint + 1]);
}
}  // namespace secondary_stream

// One endpoint as pairing sees it: its box's rank with the kind in the top bit, and the box's
// candidate range [L, U).
struct Endpoint {
  uint32_t rank_and_kind;
  uint32_t low;
  uint32_t high;
};

// Endpoint inK of the secondary order, from the box's record (a random read).
inline Endpoint endpointOfOrder(const PairingInput& inInput, std::size_t inK) {
  const uint32_t endpoint = inInput.secondary_order[inK];
  const bool is_high = endpoint >= inInput.objects;
  const RankRange& range = inInput.ranges[endpoint - (is_high ? inInput.objects : 0u)];
  return {range.rank | (is_high ? secondary_stream::kHighBit : 0u), range.low, range.high};
}

// Endpoint inK of the secondary stream (an ordered read).
inline Endpoint endpointOfStream(const uint64_t* inStream, std::size_t inK) {
  return {secondary_stream::rankAndKind(inStream, inK), secondary_stream::low(inStream, inK),
          secondary_stream::high(inStream, inK)};
}

// Writes the secondary stream of the whole order, on the scope's threads.
void buildSecondaryStream(const PairingInput& inInput) {
  const std::size_t endpoints = 2 * std::size_t{inInput.objects};
  uint64_t* stream = inInput.stream_scratch;
  runOverItems(WorkUnits{endpoints}, [&](std::size_t inBegin, std::size_t inEnd) {
    for (std::size_t k = inBegin; k < inEnd; ++k) {
      const Endpoint endpoint = endpointOfOrder(inInput, k);
      stream[2 * k] = endpoint.rank_and_kind | (uint64_t{endpoint.low} << 32);
      stream[2 * k + 1] = endpoint.high;
    }
  });
}

// Keys overlap on every axis. Without branches: all six comparisons, combined with bitwise
// operators.
inline bool keysOverlapFlat(const RankedKeys& inA, const RankedKeys& inB) {
  const bool apart = (inA.lo[0] > inB.hi[0]) | (inB.lo[0] > inA.hi[0]) | (inA.lo[1] > inB.hi[1]) |
                     (inB.lo[1] > inA.hi[1]) | (inA.lo[2] > inB.hi[2]) | (inB.lo[2] > inA.hi[2]);
  return !apart;
}

// Keys deep enough inside each other that the float64 intervals must overlap too.
inline bool keysCertainlyOverlap(const RankedKeys& inA, const RankedKeys& inB) {
  for (int axis = 0; axis < 3; ++axis) {
    if (inA.lo[axis] + kCertainKeyMargin > inB.hi[axis] ||
        inB.lo[axis] + kCertainKeyMargin > inA.hi[axis])
      return false;
  }
  return true;
}

inline bool filtersAllow(const RankedFilter& inA, const RankedFilter& inB) {
  return groupsMayPair(inA.group, inA.mask, inB.group, inB.mask);
}

// Where a sweep reads its endpoints: the whole secondary stream (Algorithm 1) or one
// partition's entry list (Algorithm 4). Both yield (rank, is_high, local candidate range).
struct WholeStreamReader {
  const uint64_t* stream;
  std::size_t count;
  uint32_t rank_end;  // ranks are local to [0, rank_end)
  std::size_t size() const { return count; }
  uint32_t rankAt(std::size_t inK) const {
    return secondary_stream::rankAndKind(stream, inK) & ~secondary_stream::kHighBit;
  }
  void read(std::size_t inK, uint32_t& outRank, bool& outHigh, uint32_t& outBegin,
            uint32_t& outEnd) const {
    const uint32_t rank_and_kind = secondary_stream::rankAndKind(stream, inK);
    outRank = rank_and_kind & ~secondary_stream::kHighBit;
    outHigh = (rank_and_kind & secondary_stream::kHighBit) != 0;
    outBegin = secondary_stream::low(stream, inK);
    outEnd = std::min(secondary_stream::high(stream, inK), rank_end);
  }
};

struct PartitionReader {
  const uint64_t* entries;
  std::size_t count;
  std::size_t size() const { return count; }
  uint32_t rankAt(std::size_t inK) const { return static_cast<uint32_t>(entries[inK]) & kRankMask; }
  void read(std::size_t inK, uint32_t& outRank, bool& outHigh, uint32_t& outBegin,
            uint32_t& outEnd) const {
    const uint64_t entry = entries[inK];
    outRank = static_cast<uint32_t>(entry) & kRankMask;
    outHigh = (entry & kEntryHighBit) != 0;
    outBegin = static_cast<uint32_t>(entry >> 31) & kLocalRankMask;
    outEnd = static_cast<uint32_t>(entry >> 47) & kLocalRankMask;
  }
};

// One partition's sweep: the paper's loop over the secondary order with the active list split
// by slab. Ranks in [inRankBegin, inRankEnd) are this sweep's; trees hold local ranks.
class PartitionSweep {
 public:
  PartitionSweep(const PairingInput& inInput, uint32_t inRankBegin, uint32_t inRankEnd,
                 SuccTree* ioTrees, PairChunks& outPairs)
      : input_(inInput),
        rank_begin_(inRankBegin),
        rank_end_(inRankEnd),
        trees_(ioTrees),
        pairs_(outPairs) {}

  template <typename Reader>
  void run(const Reader& inReader) {
    uint32_t rank = 0, begin = 0, end = 0;
    bool high = false;
    const std::size_t size = inReader.size();
    for (std::size_t k = 0; k < size; ++k) {
      // Ranks come in secondary-axis order, so the box records they index are scattered over
      // the rank arrays and each one's first touch misses the cache: fetch them ahead.
      if (k + kPrefetchAhead < size) prefetchRecords(inReader.rankAt(k + kPrefetchAhead));
      inReader.read(k, rank, high, begin, end);
      const RankedSlabs slabs = slabsOf(rank);
      const bool own_rank = rank >= rank_begin_ && rank < rank_end_;
      SAP_ASSERT(slabs.first <= slabs.last && slabs.last < input_.slab_count,
                 "a box's slabs out of the grid");
      if (high) {
        SAP_ASSERT(!own_rank || trees_[slabs.first].contains(rank - rank_begin_),
                   "a high endpoint of a box that is not in its slab's active list");
        for (int slab = slabs.first; slab <= slabs.last; ++slab)
          trees_[slab].erase(rank - rank_begin_);
        continue;
      }
      // A box's own rank lies in its candidate range (L <= R < U), clipped to this sweep's.
      SAP_ASSERT(!own_rank || (begin <= rank - rank_begin_ && rank - rank_begin_ < end),
                 "a low endpoint whose candidate range misses its own rank");
      SAP_ASSERT(end <= rank_end_ - rank_begin_, "a candidate range beyond the sweep's ranks");
      if (begin < end) {
        const uint32_t object = input_.object_of_rank[rank];
        for (int slab = slabs.first; slab <= slabs.last; ++slab)
          testCandidates(slab, begin, end, object, rank);
      }
      if (own_rank)
        for (int slab = slabs.first; slab <= slabs.last; ++slab)
          trees_[slab].insert(rank - rank_begin_);
    }
  }

 private:
  static constexpr std::size_t kPrefetchAhead = tuning::kEndpointPrefetchAhead;

  void prefetchRecords(uint32_t inRank) const {
    __builtin_prefetch(&input_.keys[inRank]);
    __builtin_prefetch(&input_.object_of_rank[inRank]);
    if (input_.slabs) __builtin_prefetch(&input_.slabs[inRank]);
  }

  RankedSlabs slabsOf(uint32_t inRank) const {
    return input_.slabs ? input_.slabs[inRank] : RankedSlabs{0, 0};
  }

  // Tests box inObject (rank inRank) against slab inSlab's active ranks in [inBegin, inEnd).
  // Two stages: a branch-free filter over the candidates the tree yields (slab rule and key
  // test, whose outcomes are close to random and mispredicted about half the time as branches)
  // compacts the survivors into a small buffer; only those, a few percent of the candidates,
  // take the exact test, the filters and the output, with branches.
  void testCandidates(int inSlab, uint32_t inBegin, uint32_t inEnd, uint32_t inObject,
                      uint32_t inRank) {
    const RankedKeys keys = input_.keys[inRank];
    const RankedKeys* all_keys = input_.keys;
    const RankedSlabs* slabs = input_.slabs;
    const uint32_t slab = static_cast<uint32_t>(inSlab);
    const uint32_t first_slab = slabs ? slabs[inRank].first : 0;
    const uint32_t rank_begin = rank_begin_;
    uint32_t survivors[kSurvivorBlock];
    uint32_t count = 0;
    trees_[inSlab].forEachInRange(inBegin, inEnd, [&](uint32_t inLocalRank) {
      const uint32_t other_rank = inLocalRank + rank_begin;
      bool keep = keysOverlapFlat(keys, all_keys[other_rank]);
      // A pair sharing several slabs is reported only in the slab of the larger low end.
      if (slabs) keep &= slab == std::max<uint32_t>(first_slab, slabs[other_rank].first);
      survivors[count] = other_rank;
      count += keep;
      if (count == kSurvivorBlock) {
        reportSurvivors(survivors, count, keys, inObject, inRank);
        count = 0;
      }
    });
    reportSurvivors(survivors, count, keys, inObject, inRank);
  }

  // Exact test (float64, for keys too close to decide), filters and output of candidates whose
  // keys overlap.
  void reportSurvivors(const uint32_t* inRanks, uint32_t inCount, const RankedKeys& inKeys,
                       uint32_t inObject, uint32_t inRank) {
    const RankedFilter* filters = input_.filters;
    for (uint32_t k = 0; k < inCount; ++k) {
      const uint32_t other_rank = inRanks[k];
      const uint32_t other = input_.object_of_rank[other_rank];
      if (input_.boxes && !keysCertainlyOverlap(inKeys, input_.keys[other_rank]) &&
          !boxesOverlap(*input_.boxes, inObject, other))
        continue;
      if (filters && !filtersAllow(filters[inRank], filters[other_rank])) continue;
      pairs_.push_back(makeIdPair(input_.ids[inObject], input_.ids[other]));
    }
  }

  static constexpr uint32_t kSurvivorBlock = tuning::kSurvivorBlock;

  const PairingInput& input_;
  const uint32_t rank_begin_;
  const uint32_t rank_end_;
  SuccTree* const trees_;
  PairChunks& pairs_;
};

// The split of rank space into partitions of 2^shift ranks (a power of two, so that finding
// an endpoint's partitions is a shift, not a division: the scatter does it twice an endpoint).
struct RankPartitions {
  uint32_t shift = 0;
  uint32_t count = 0;
  uint32_t size() const { return uint32_t{1} << shift; }
  uint32_t of(uint32_t inRank) const { return inRank >> shift; }
  uint32_t begin(uint32_t inPartition) const { return inPartition << shift; }
};

// All ones when an endpoint is a high endpoint, else 0.
inline uint32_t highMask(uint32_t inRankAndKind) {
  static_assert(secondary_stream::kHighBit == 0x80000000u, "the kind is the top bit");
  return 0u - (inRankAndKind >> 31);
}

// The rank partitions an endpoint matters to: its own (insert, erase) and, for a low endpoint,
// every partition its candidate range [L, U) reaches (which includes its own: L <= R < U).
// Lows and highs alternate at random in the order, so both are computed without a branch.
inline void partitionsOf(const Endpoint& inEndpoint, const RankPartitions& inSplit,
                         uint32_t& outFirst, uint32_t& outLast) {
  const uint32_t rank = inEndpoint.rank_and_kind & ~secondary_stream::kHighBit;
  // All ones for a high endpoint: the selections are masks, since the compiler turns a
  // conditional expression back into a branch.
  const uint32_t high = highMask(inEndpoint.rank_and_kind);
  const uint32_t low_first = std::min(inEndpoint.low, rank);
  const uint32_t low_last = std::max(inEndpoint.high, rank + 1) - 1;
  outFirst = inSplit.of((rank & high) | (low_first & ~high));
  outLast = inSplit.of((rank & high) | (low_last & ~high));
}

// The entry of an endpoint for partition inPartition (branch-free, as above).
inline uint64_t entryFor(const Endpoint& inEndpoint, uint32_t inPartition,
                         const RankPartitions& inSplit) {
  const uint32_t rank = inEndpoint.rank_and_kind & ~secondary_stream::kHighBit;
  const uint32_t partition_begin = inSplit.begin(inPartition);
  const uint32_t partition_end = partition_begin + inSplit.size();
  const uint32_t begin = std::max(inEndpoint.low, partition_begin);
  const uint32_t end = std::min(inEndpoint.high, partition_end);
  const uint64_t low_entry =
      lowEntry(rank, begin - partition_begin, std::max(begin, end) - partition_begin);
  const uint64_t high = uint64_t{0} - (inEndpoint.rank_and_kind >> 31);  // all ones: high
  return (highEntry(rank) & high) | (low_entry & ~high);
}

// Slice inSlice of inSlices of the secondary order, [outBegin, outEnd): the same every frame
// for the same n and slice count, so that a segment's size carries over from frame to frame.
// Slices are work units (more than threads, claimed dynamically), so the layout never
// depends on the team's size.
inline void sliceOf(uint32_t inObjects, int inSlice, int inSlices, std::size_t& outBegin,
                    std::size_t& outEnd) {
  const std::size_t endpoints = 2 * std::size_t{inObjects};
  outBegin = endpoints * inSlice / inSlices;
  outEnd = endpoints * (inSlice + 1) / inSlices;
}

// Each slice's counters sit a cache line past the previous slice's (no false sharing).
inline std::size_t counterStride(uint32_t inPartitions) {
  return 2 * std::size_t{inPartitions} + kCacheLineBytes / sizeof(std::size_t);
}

// The counted scatter fills each segment exactly: it ends where the next one begins, and the
// last one ends the entries.
[[maybe_unused]] bool segmentsArePacked(const SweepWorkspace& inWork, uint32_t inPartitions,
                                        int inSlices) {
  const std::size_t segments = std::size_t(inPartitions) * inSlices;
  for (std::size_t s = 0; s < segments; ++s) {
    const std::size_t next =
        s + 1 < segments ? inWork.segment_begin[s + 1] : inWork.partition_entries.size();
    if (inWork.segment_end[s] != next) return false;
  }
  return true;
}

// Calls inVisit(endpoint, first, last) for each endpoint of slice inSlice of the secondary
// stream, in stream order, with the partitions [first, last] it matters to: the counting and
// the placement passes of the counted scatter visit the same endpoints the same way.
template <class Visit>
void forEachEndpointOfSlice(const PairingInput& inInput, const uint64_t* inStream, int inSlice,
                            int inSlices, const RankPartitions& inSplit, Visit&& inVisit) {
  std::size_t begin = 0, end = 0;
  sliceOf(inInput.objects, inSlice, inSlices, begin, end);
  uint32_t first = 0, last = 0;
  for (std::size_t k = begin; k < end; ++k) {
    const Endpoint endpoint = endpointOfStream(inStream, k);
    partitionsOf(endpoint, inSplit, first, last);
    inVisit(endpoint, first, last);
  }
}

// Scatter from the exact counts: the secondary stream, a counting pass over it, then the
// placement pass. Segments are packed without gaps. Also estimates each partition's work, its
// entries plus the candidate ranks its low entries span, into ioWork.partition_work.
void scatterCounted(const PairingInput& inInput, int inSlices, const RankPartitions& inSplit,
                    SweepWorkspace& ioWork) {
  buildSecondaryStream(inInput);
  const uint64_t* stream = inInput.stream_scratch;
  const uint32_t partitions = inSplit.count;
  std::vector<std::size_t>& counts = ioWork.scatter_counts;
  const std::size_t stride = counterStride(partitions);
  counts.assign(std::size_t(inSlices) * stride, 0);
  ioWork.partition_work.assign(partitions, 0);
  runUnits(inSlices, [&](std::size_t inSlice) {
    // Entry counts at [0, partitions), work at [partitions, 2 * partitions).
    std::size_t* my_counts = &counts[inSlice * stride];
    std::size_t* my_work = my_counts + partitions;
    forEachEndpointOfSlice(inInput, stream, static_cast<int>(inSlice), inSlices, inSplit,
                           [&](const Endpoint& inEndpoint, uint32_t inFirst, uint32_t inLast) {
                             for (uint32_t p = inFirst; p <= inLast; ++p)
                               ++my_counts[p];  // rare: ranges are short
                             // A low endpoint's candidate ranks, charged to the partition where its
                             // range starts.
                             my_work[inFirst] += (inEndpoint.high - inEndpoint.low) &
                                                 ~highMask(inEndpoint.rank_and_kind);
                           });
  });
  std::size_t offset = 0;
  for (uint32_t p = 0; p < partitions; ++p) {
    const std::size_t partition_begin = offset;
    std::size_t work = 0;
    for (int slice = 0; slice < inSlices; ++slice) {
      std::size_t& slot = counts[std::size_t(slice) * stride + p];
      const std::size_t size = slot;
      ioWork.segment_begin[std::size_t(p) * inSlices + slice] = offset;
      slot = offset;
      offset += size;
      work += counts[std::size_t(slice) * stride + partitions + p];
    }
    ioWork.partition_work[p] = work + (offset - partition_begin);
  }
  resizeDiscarding(ioWork.partition_entries, offset);
  uint64_t* out = ioWork.partition_entries.data();
  runUnits(inSlices, [&](std::size_t inSlice) {
    const int slice = static_cast<int>(inSlice);
    std::size_t* my_counts = &counts[inSlice * stride];
    forEachEndpointOfSlice(inInput, stream, slice, inSlices, inSplit,
                           [&](const Endpoint& inEndpoint, uint32_t inFirst, uint32_t inLast) {
                             for (uint32_t p = inFirst; p <= inLast; ++p)
                               out[my_counts[p]++] = entryFor(inEndpoint, p, inSplit);
                           });
    for (uint32_t p = 0; p < partitions; ++p)
      ioWork.segment_end[std::size_t(p) * inSlices + slice] = my_counts[p];
  });

  SAP_ASSERT(segmentsArePacked(ioWork, partitions, inSlices),
             "the counted scatter left a gap or an overlap between segments");
}

// Room a segment gets beyond its size in the last frame (tuning.h).
inline std::size_t segmentRoom(std::size_t inLastSize) {
  return inLastSize + inLastSize / tuning::kSegmentRoomShare + tuning::kSegmentRoomEntries;
}

constexpr std::size_t kScatterPrefetchAhead = tuning::kEndpointPrefetchAhead;

// Scatters slice inSlice straight from the secondary order and the boxes' records into the
// segments' room. Returns false when a segment outgrew its room.
bool scatterSliceIntoRoom(const PairingInput& inInput, int inSlice, int inSlices,
                          const RankPartitions& inSplit, std::size_t* ioCursor,
                          SweepWorkspace& ioWork) {
  const uint32_t partitions = inSplit.count;
  const std::size_t segments = std::size_t(partitions) * inSlices;
  // Next free entry at [0, partitions), end of the segment's room at [partitions, 2 *
  // partitions).
  std::size_t* cursor = ioCursor;
  std::size_t* limit = ioCursor + partitions;
  for (uint32_t p = 0; p < partitions; ++p) {
    const std::size_t segment = std::size_t(p) * inSlices + inSlice;
    cursor[p] = ioWork.segment_begin[segment];
    limit[p] = segment + 1 < segments ? ioWork.segment_begin[segment + 1]
                                      : ioWork.partition_entries.size();
  }
  std::size_t begin = 0, end = 0;
  sliceOf(inInput.objects, inSlice, inSlices, begin, end);
  uint64_t* out = ioWork.partition_entries.data();
  const uint32_t objects = inInput.objects;
  uint32_t first = 0, last = 0;
  bool fits = true;
  for (std::size_t k = begin; k < end && fits; ++k) {
    // The records are read in secondary order, at random: fetch them ahead.
    if (k + kScatterPrefetchAhead < end) {
      const uint32_t ahead = inInput.secondary_order[k + kScatterPrefetchAhead];
      __builtin_prefetch(&inInput.ranges[ahead - (ahead >= objects ? objects : 0u)]);
    }
    const Endpoint endpoint = endpointOfOrder(inInput, k);
    partitionsOf(endpoint, inSplit, first, last);
    for (uint32_t p = first; p <= last; ++p) {
      if (cursor[p] == limit[p]) {
        fits = false;
        break;
      }
      out[cursor[p]++] = entryFor(endpoint, p, inSplit);
    }
  }
  for (uint32_t p = 0; p < partitions; ++p) {
    SAP_ASSERT(cursor[p] <= limit[p], "the one-pass scatter wrote past a segment's room");
    ioWork.segment_end[std::size_t(p) * inSlices + inSlice] = cursor[p];
  }
  return fits;
}

// Scatter in one pass, straight from the secondary order and the boxes' records, into
// segments sized from the last frame's (no stream, no counting pass). Returns false, with the
// entries incomplete, when a segment outgrew its room: then the caller scatters counted.
bool scatterIntoLastLayout(const PairingInput& inInput, int inSlices, const RankPartitions& inSplit,
                           SweepWorkspace& ioWork) {
  const std::size_t segments = std::size_t(inSplit.count) * inSlices;
  std::size_t offset = 0;
  for (std::size_t s = 0; s < segments; ++s) {
    ioWork.segment_begin[s] = offset;
    offset += segmentRoom(ioWork.last_layout.segment_used[s]);
    SAP_ASSERT(segmentRoom(ioWork.last_layout.segment_used[s]) > ioWork.last_layout.segment_used[s],
               "a segment's room does not exceed its last size");
  }
  resizeDiscarding(ioWork.partition_entries, offset);
  const std::size_t stride = counterStride(inSplit.count);
  ioWork.scatter_counts.assign(std::size_t(inSlices) * stride, 0);
  std::vector<uint8_t> slice_fits(static_cast<std::size_t>(inSlices), 1);
  runUnits(inSlices, [&](std::size_t inSlice) {
    const int slice = static_cast<int>(inSlice);
    std::size_t* cursor = &ioWork.scatter_counts[std::size_t(slice) * stride];
    slice_fits[inSlice] = scatterSliceIntoRoom(inInput, slice, inSlices, inSplit, cursor, ioWork);
  });
  return std::all_of(slice_fits.begin(), slice_fits.end(), [](uint8_t inFits) { return inFits; });
}

// Copies each endpoint of the secondary order to the entry segments of the partitions it
// matters to, keeping sweep order within each (slice s's segment of a partition holds the
// entries of slice s of the order, so the segments in slice order are in sweep order), the
// inSlices slices on the scope's threads. When the last frame had the same split, straight
// into its layout; otherwise, or when a segment outgrows it, counted.
void scatterToPartitions(const PairingInput& inInput, int inSlices, const RankPartitions& inSplit,
                         SweepWorkspace& ioWork) {
  const std::size_t segments = std::size_t(inSplit.count) * inSlices;
  ioWork.segment_begin.resize(segments);
  ioWork.segment_end.resize(segments);
  ScatterLayout& layout = ioWork.last_layout;
  const bool same_split = layout.slices == inSlices && layout.shift == inSplit.shift &&
                          layout.partitions == inSplit.count;
  if (!same_split || !scatterIntoLastLayout(inInput, inSlices, inSplit, ioWork))
    scatterCounted(inInput, inSlices, inSplit, ioWork);
  if (!same_split) layout.partition_ms.assign(inSplit.count, 0.0);
  layout.slices = inSlices;
  layout.shift = inSplit.shift;
  layout.partitions = inSplit.count;
  layout.segment_used.resize(segments);
  for (std::size_t s = 0; s < segments; ++s) {
    SAP_ASSERT(ioWork.segment_begin[s] <= ioWork.segment_end[s] &&
                   ioWork.segment_end[s] <= ioWork.partition_entries.size(),
               "a scattered segment out of the entries");
    layout.segment_used[s] = ioWork.segment_end[s] - ioWork.segment_begin[s];
  }
}

// Makes trees [inFirst, inFirst + inCount) of ioTrees empty trees over inSize ranks.
void prepareTrees(std::vector<SuccTree>& ioTrees, std::size_t inFirst, int inCount,
                  uint32_t inSize) {
  if (ioTrees.size() < inFirst + inCount) ioTrees.resize(inFirst + inCount);
  for (int t = 0; t < inCount; ++t) {
    SuccTree& tree = ioTrees[inFirst + t];
    if (tree.size() != inSize) tree.resize(inSize);  // same size: left empty by the last sweep
  }
}

// The rank split: partitions of at most tuning::kPairingPartitionRanks ranks, and on several
// threads (the scope's) at least tuning::kPairingPartitionsPerThread per thread, so that handing
// the partitions out by decreasing measured work evens the threads out on clustered frames too. The
// size is the largest power of two that gives at least that many partitions.
RankPartitions partitionRanks(uint32_t inObjects) {
  const int threads = passThreads();
  const uint32_t by_cache =
      (inObjects + tuning::kPairingPartitionRanks - 1) / tuning::kPairingPartitionRanks;
  const uint32_t by_threads = threads > 1 ? threads * tuning::kPairingPartitionsPerThread : 1;
  const uint32_t wanted = std::max(by_cache, by_threads);
  const uint32_t largest_size = std::max<uint32_t>(1, (inObjects + wanted - 1) / wanted);
  RankPartitions split;
  while ((uint32_t{2} << split.shift) <= largest_size) ++split.shift;
  split.count = (inObjects + split.size() - 1) >> split.shift;
  SAP_ASSERT(split.size() <= tuning::kPairingPartitionRanks,
             "a partition's local ranks exceed 16 bits");
  // The partitions cover every rank, and none lies wholly beyond the last rank.
  SAP_ASSERT(uint64_t{split.count} * split.size() >= inObjects &&
                 (split.count == 0 || uint64_t{split.count - 1} * split.size() < inObjects),
             "the rank partitions do not cover ranks 0..n-1 exactly");
  return split;
}

// Every box a sweep inserted it erased again: the trees are left empty for the next sweep.
[[maybe_unused]] bool treesAreEmpty(const SuccTree* inTrees, int inCount) {
  for (int t = 0; t < inCount; ++t)
    if (!inTrees[t].empty()) return false;
  return true;
}

// Sweeps partition inPartition of the scattered entries, segment after segment, with ioTrees
// (slab_count trees of the partition's size, left empty again by the sweep), and records how
// long it took.
void sweepPartition(const PairingInput& inInput, SweepWorkspace& ioWork,
                    const RankPartitions& inSplit, int inSlices, uint32_t inPartition,
                    SuccTree* ioTrees, PairChunks& outPairs) {
  const Clock::time_point start = Clock::now();
  const uint32_t rank_begin = inSplit.begin(inPartition);
  const uint32_t rank_end = std::min(inInput.objects, rank_begin + inSplit.size());
  PartitionSweep sweep(inInput, rank_begin, rank_end, ioTrees, outPairs);
  for (int slice = 0; slice < inSlices; ++slice) {
    const std::size_t segment = std::size_t(inPartition) * inSlices + slice;
    const std::size_t begin = ioWork.segment_begin[segment];
    const std::size_t end = ioWork.segment_end[segment];
    sweep.run(PartitionReader{ioWork.partition_entries.data() + begin, end - begin});
  }
  SAP_ASSERT(treesAreEmpty(ioTrees, inInput.slab_count),
             "a partition's sweep left boxes in its active lists");
  ioWork.last_layout.partition_ms[inPartition] = millisecondsSince(start);
}

// The order the partitions are handed out in: largest work first, so that the last ones
// handed out are the small ones and the threads finish together (longest-processing-time-first
// on a dynamic schedule). The work is the partition's measured sweep time in the last frame
// where there was one with this split (frames change little from one to the next), else the
// estimate of the counting scatter.
void orderPartitions(const RankPartitions& inSplit, SweepWorkspace& ioWork) {
  std::vector<uint32_t>& order = ioWork.partition_order;
  order.resize(inSplit.count);
  std::iota(order.begin(), order.end(), 0u);
  const std::vector<double>& measured = ioWork.last_layout.partition_ms;
  if (std::all_of(measured.begin(), measured.end(), [](double inMs) { return inMs > 0.0; })) {
    std::sort(order.begin(), order.end(),
              [&](uint32_t inA, uint32_t inB) { return measured[inA] > measured[inB]; });
  } else {
    const std::vector<std::size_t>& estimate = ioWork.partition_work;
    std::sort(order.begin(), order.end(),
              [&](uint32_t inA, uint32_t inB) { return estimate[inA] > estimate[inB]; });
  }
}

// inOrder holds 0..inCount-1, each once: every partition is swept exactly once.
[[maybe_unused]] bool isPermutation(const std::vector<uint32_t>& inOrder, uint32_t inCount) {
  std::vector<uint8_t> seen(inCount, 0);
  for (const uint32_t partition : inOrder) {
    if (partition >= inCount || seen[partition]) return false;
    seen[partition] = 1;
  }
  return inOrder.size() == inCount;
}

}  // namespace

void pairSequential(const PairingInput& inInput, SweepWorkspace& ioWork, PairChunks& outPairs) {
  const NarrowedScope one_thread(1);  // Algorithm 1: every pass of it on the calling thread
  const uint32_t n = inInput.objects;
  if (n <= tuning::kPairingPartitionRanks ||
      uint64_t{n} * static_cast<uint64_t>(inInput.slab_count) <= tuning::kSequentialTreeBits) {
    outPairs.setBudget(inInput.pair_budget);
    buildSecondaryStream(inInput);
    prepareTrees(ioWork.pairing, 0, inInput.slab_count, n);
    PartitionSweep sweep(inInput, 0, n, ioWork.pairing.data(), outPairs);
    sweep.run(WholeStreamReader{inInput.stream_scratch, 2 * std::size_t{n}, n});
    SAP_ASSERT(treesAreEmpty(ioWork.pairing.data(), inInput.slab_count),
               "the sweep left boxes in its active lists");
    return;
  }
  // Trees over all n ranks (times the slabs) too big for the cache: one thread sweeps
  // partition by partition, as Algorithm 4 does. The scatter pass costs one read of the
  // order; on the big trees every insert, erase and range walk would miss the cache.
  outPairs.setBudget(inInput.pair_budget);
  const RankPartitions split = partitionRanks(n);
  scatterToPartitions(inInput, 1, split, ioWork);
  prepareTrees(ioWork.pairing, 0, inInput.slab_count, split.size());
  for (uint32_t p = 0; p < split.count; ++p)
    sweepPartition(inInput, ioWork, split, 1, p, ioWork.pairing.data(), outPairs);
}

void pairParallel(const PairingInput& inInput, SweepWorkspace& ioWork,
                  std::vector<PairChunks>& outPairsPerThread) {
  const int threads = std::max(1, passThreads());
  const RankPartitions split = partitionRanks(inInput.objects);  // Δ and m
  const int slices = unitsForThreads(threads);
  scatterToPartitions(inInput, slices, split, ioWork);
  orderPartitions(split, ioWork);
  SAP_ASSERT(isPermutation(ioWork.partition_order, split.count),
             "partitions handed out twice or never");
  const int slab_count = inInput.slab_count;
  prepareTrees(ioWork.pairing, 0, threads * slab_count, split.size());
  outPairsPerThread.resize(threads);
  for (PairChunks& pairs : outPairsPerThread) {
    pairs.clear();  // a smaller team leaves some
    pairs.setBudget(inInput.pair_budget);
  }
  // Each worker sweeps its partitions with its own trees into its own pair list.
  runUnitsOnWorkers(split.count, [&](std::size_t inK, int inWorker) {
    // Past max_pairs a worker's trees may hold the boxes of the partition it stopped in.
    if (inInput.pair_budget && inInput.pair_budget->exhausted()) return;
    SuccTree* trees = &ioWork.pairing[std::size_t(inWorker) * slab_count];
    PairChunks& pairs = outPairsPerThread[inWorker];
    sweepPartition(inInput, ioWork, split, slices, ioWork.partition_order[inK], trees, pairs);
  });
}

}  // namespace sap_broadphase
