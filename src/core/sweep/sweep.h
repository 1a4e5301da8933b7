// The sweep phases of the paper: Algorithm 1 (sequential bi-dimensional SaP), Algorithm 3
// (parallel candidate generation on the primary axis) and Algorithm 4 (parallel pairing on the
// secondary axis). Objects are box indexes 0..n-1; sorted orders hold endpoint indexes, with
// object i's low endpoint at i and its high endpoint at i + n.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/frame/box_columns.h"
#include "core/frame/pair_sort.h"
#include "core/runner/buffers.h"
#include "core/sweep/slab_grid.h"
#include "core/sweep/succ_tree.h"
#include "core/tuning.h"

namespace sap_broadphase {

/// Per object: its rank R[i] (position of its low endpoint among the primary-axis lows) and
/// its candidate range [L[i], U[i]) of ranks (Algorithm 1, lines 8-13).
struct RankRange {
  uint32_t rank;
  uint32_t low;   ///< L[i]: least rank active when i starts (or R[i] when none is)
  uint32_t high;  ///< U[i]: number of lows seen when i ends (exclusive bound)
};

/// Ranks and candidate ranges of all objects, plus the inverse of the rank (R^- in the paper).
struct CandidateRanges {
  Buffer<RankRange> of_object;      ///< indexed by object
  Buffer<uint32_t> object_of_rank;  ///< R^-
};

/// Group and mask of one box, in rank order (only built when filters are in use).
struct RankedFilter {
  uint32_t group;
  uint32_t mask;
};

/// Float32 keys of one box rounded outward (sort_keys.h), in rank order, so that candidates
/// with nearby ranks sit in nearby memory. Keys that overlap with a margin of
/// kCertainKeyMargin on every axis prove an exact overlap; keys apart prove a miss; only
/// near-touching boxes need the float64 test on the input.
struct RankedKeys {
  uint32_t lo[3];
  uint32_t hi[3];
};

/// Keys that far inside each other's interval prove an exact overlap: a low key is at most two
/// keys below the smallest float >= the low end, a high key at most two above the largest
/// float <= the high end.
constexpr uint32_t kCertainKeyMargin = 4;

/// First and last slab a box touches, in rank order.
struct RankedSlabs {
  uint8_t first;
  uint8_t last;
};
static_assert(kMaxSlabs - 1 <= 0xFF, "slab numbers are stored in 8 bits");

/// What pairing needs to know about the boxes.
struct PairingInput {
  const uint32_t* secondary_order = nullptr;  ///< the 2n endpoints in secondary-axis order
  const RankRange* ranges = nullptr;          ///< rank and candidate range, by object
  uint64_t* stream_scratch = nullptr;         ///< room for 4n words, which pairing may overwrite
  uint32_t objects = 0;                       ///< n
  const uint32_t* object_of_rank = nullptr;   ///< R^-
  const RankedKeys* keys = nullptr;           ///< outward keys by rank
  const BoxColumns* boxes = nullptr;  ///< exact float64 test for near-touching keys; null in the
                                      ///< keys-only mode, where overlapping keys are reported
  const RankedFilter* filters = nullptr;  ///< null when no box has a group or mask
  const uint32_t* ids = nullptr;          ///< box ids, by object index
  const RankedSlabs* slabs = nullptr;     ///< null when slab_count is 1
  int slab_count = 1;
  PairBudget* pair_budget = nullptr;  ///< the frame's bound on pairs (max_pairs); null: none
};

/// How the last frame's pairing scatter laid out its entries: the split and thread count it
/// was for, and how many entries each (partition, thread) segment held.
struct ScatterLayout {
  int slices = 0;  ///< slices of the secondary order (work units, more than threads)
  uint32_t shift = 0;
  uint32_t partitions = 0;
  std::vector<std::size_t> segment_used;  ///< [partition * slices + slice]
  std::vector<double> partition_ms;       ///< measured sweep time of each partition
};

/// Reusable buffers of the parallel phases.
struct SweepWorkspace {
  Buffer<uint64_t> slice_objects;      ///< Algorithm 3: per slice, objects with one endpoint in it
  std::vector<SuccTree> slice_start;   ///< Algorithm 3: ranks active at the slice's start
  std::vector<uint32_t> lows_before;   ///< Algorithm 3: rank counter at the slice's start
  std::vector<SuccTree> pairing;       ///< Algorithm 4: slab_count trees per thread
  Buffer<uint64_t> partition_entries;  ///< Algorithm 4: endpoints by partition
  /// Algorithm 4: each partition's entries are one segment per slice of the secondary order,
  /// [segment_begin, segment_end), [partition * slices + slice].
  std::vector<std::size_t> segment_begin;
  std::vector<std::size_t> segment_end;
  std::vector<std::size_t> scatter_counts;  ///< [slice][partition] counters and limits
  std::vector<std::size_t> partition_work;  ///< Algorithm 4: estimated work per partition
  std::vector<uint32_t> partition_order;    ///< Algorithm 4: partitions by decreasing work
  ScatterLayout last_layout;                ///< Algorithm 4: the last frame's scatter
};

/// Algorithm 1, lines 5-14: ranks and candidate ranges from the primary-axis order, one thread.
void computeCandidatesSequential(const uint32_t* inPrimaryOrder, uint32_t inObjects,
                                 SuccTree& ioActive, CandidateRanges& outRanges);

/// Algorithm 3: the same result computed by the scope's threads (passThreads()) on equal slices of
/// the order (more slices than threads, claimed dynamically), with per-slice sets (of objects, not
/// ranks) joined by an all-prefix symmetric difference.
void computeCandidatesParallel(const uint32_t* inPrimaryOrder, uint32_t inObjects,
                               SweepWorkspace& ioWork, CandidateRanges& outRanges);

/// Algorithm 1, lines 15-23: every pair, found once, by one thread. Appends to outPairs. When
/// the trees would exceed tuning::kSequentialTreeBits, the thread sweeps the partitions of
/// pairParallel one after another instead, so that its trees stay in cache.
void pairSequential(const PairingInput& inInput, SweepWorkspace& ioWork, PairChunks& outPairs);

/// Algorithm 4: rank space split into partitions of at most tuning::kPairingPartitionRanks ranks
/// (and at least tuning::kPairingPartitionsPerThread per thread), each swept by one thread with its
/// own SuccTrees, handed out largest work first (the sweep time each took in the last frame with
/// this split, else an estimate); each pair is found in exactly one partition, without locks
/// or reduction. Unlike the paper, where every thread reads all 2n endpoints, a scatter first
/// hands each partition only the endpoints that touch it (those whose rank or candidate range
/// falls in it), in sweep order, packed in 8 bytes: partitions then fit in cache and there may
/// be many more of them than threads. On coherent frames the scatter is one pass straight
/// into room sized from the last frame's segments.
/// outPairsPerThread[t] receives thread t's pairs.
void pairParallel(const PairingInput& inInput, SweepWorkspace& ioWork,
                  std::vector<PairChunks>& outPairsPerThread);

}  // namespace sap_broadphase
