// The sweep phases of the paper: Algorithm 1 (sequential bi-dimensional SaP), Algorithm 3
// (parallel candidate generation on the primary axis) and Algorithm 4 (parallel pairing on the
// secondary axis). Objects are box indexes 0..n-1; sorted orders hold endpoint indexes, with
// object i's low endpoint at i and its high endpoint at i + n.
#pragma once

#include <cstdint>
#include <vector>

#include "sap_broadphase/core/pair_set.h"
#include "sap_broadphase/core/slab_grid.h"
#include "sap_broadphase/core/succ_tree.h"

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
  std::vector<RankRange> of_object;      ///< indexed by object
  std::vector<uint32_t> object_of_rank;  ///< R^-
};

/// Exact bounds of one box, stored in primary-rank order so that candidates with nearby ranks
/// sit in nearby memory.
struct RankedBox {
  double lo[3];
  double hi[3];
};

/// Group and mask of one box, in rank order (only built when filters are in use).
struct RankedFilter {
  uint32_t group;
  uint32_t mask;
};

/// Float32 keys of one box rounded outward, in rank order (the keys-only mode's test).
struct RankedKeys {
  uint32_t lo[3];
  uint32_t hi[3];
};

/// First and last slab a box touches, in rank order.
struct RankedSlabs {
  uint8_t first;
  uint8_t last;
};

/// One endpoint of the secondary-axis order with all that pairing reads about its box, laid
/// out in sweep order: every pairing thread streams through it instead of looking boxes up
/// at random (one gather pass builds it for all threads).
struct SecondaryEndpoint {
  uint32_t rank_and_kind;  ///< primary rank; bit 31 set for a high endpoint
  uint32_t low;            ///< L of the box
  uint32_t high;           ///< U of the box
  RankedSlabs slabs;       ///< third-axis slabs of the box ({0, 0} without slabs)
  static constexpr uint32_t kHighBit = 0x80000000u;
};

/// Builds the secondary stream from the sorted secondary order (inThreads threads).
void buildSecondaryStream(const uint32_t* inSecondaryOrder, uint32_t inObjects,
                          const CandidateRanges& inRanges, const RankedSlabs* inSlabs,
                          int inThreads, std::vector<SecondaryEndpoint>& outStream);

/// What pairing needs to know about the boxes, all indexed by rank.
struct PairingInput {
  const SecondaryEndpoint* stream = nullptr;  ///< 2n endpoints in secondary-axis order
  uint32_t objects = 0;                       ///< n
  const uint32_t* object_of_rank = nullptr;   ///< R^-
  const RankedBox* boxes = nullptr;           ///< exact test (null in keys-only mode)
  const RankedKeys* keys = nullptr;           ///< keys-only test (null in exact mode)
  const RankedFilter* filters = nullptr;      ///< null when no box has a group or mask
  const uint32_t* ids = nullptr;              ///< box ids, by object index
  const RankedSlabs* slabs = nullptr;         ///< null when slab_count is 1
  int slab_count = 1;
};

/// Largest rank partition of the parallel pairing: its slab trees stay cache-resident.
constexpr uint32_t kPairingPartitionRanks = 1u << 16;

/// Reusable SuccTrees of the parallel phases.
struct SweepWorkspace {
  std::vector<SuccTree> partition_local;  ///< Algorithm 3: toggled within each partition
  std::vector<SuccTree> partition_start;  ///< Algorithm 3: ⊕-prefix, active at partition start
  std::vector<SuccTree> pairing;          ///< Algorithm 4: slab_count trees per thread
  std::vector<SecondaryEndpoint> partition_streams;  ///< Algorithm 4: endpoints by partition
  std::vector<std::size_t> partition_offsets;        ///< start of each partition's stream, m + 1
  std::vector<std::size_t> scatter_counts;           ///< [thread][partition] placement counters
  std::vector<uint32_t> lows_before;  ///< Algorithm 3: rank counter at partition start
};

/// Algorithm 1, lines 5-14: ranks and candidate ranges from the primary-axis order, one thread.
void computeCandidatesSequential(const uint32_t* inPrimaryOrder, uint32_t inObjects,
                                 SuccTree& ioActive, CandidateRanges& outRanges);

/// Algorithm 3: the same result computed by inThreads threads on equal slices of the order,
/// with per-slice SuccTrees joined by an all-prefix symmetric difference.
void computeCandidatesParallel(const uint32_t* inPrimaryOrder, uint32_t inObjects, int inThreads,
                               SweepWorkspace& ioWork, CandidateRanges& outRanges);

/// Algorithm 1, lines 15-23: every pair, found once, by one thread. Appends to outPairs.
void pairSequential(const PairingInput& inInput, SweepWorkspace& ioWork, PairList& outPairs);

/// Algorithm 4: rank space split into partitions of at most kPairingPartitionRanks ranks (and at
/// least one per thread), each swept by one thread with its own SuccTrees; each pair is found in
/// exactly one partition, without locks or reduction. Unlike the paper, where every thread reads
/// all 2n endpoints, one scatter pass first hands each partition only the endpoints that touch
/// it (those whose rank or candidate range falls in it), in sweep order: partitions then fit in
/// cache and there may be many more of them than threads. outPairsPerThread[t] receives
/// thread t's pairs.
void pairParallel(const PairingInput& inInput, int inThreads, SweepWorkspace& ioWork,
                  std::vector<PairList>& outPairsPerThread);

}  // namespace sap_broadphase
