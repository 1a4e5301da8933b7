// The sweep strategy: one frame of the paper's pipeline on a box set, with the state it
// carries from frame to frame (partition bounds B, sweep axes, key origins) and every buffer
// it needs (no allocation per frame once sizes are stable).
//
//   keys (relative to the frame) -> Algorithm 2 sort of the primary axis -> Algorithm 3
//   candidates -> Algorithm 2 sort of the secondary axis -> Algorithm 4 pairing (exact 3-axis
//   test) -> pairs in canonical order -> §5 axis decision
#pragma once

#include <cstdint>
#include <vector>

#include "core/frame/pair_sort.h"
#include "core/runner/buffers.h"
#include "core/sweep/key_origin.h"
#include "core/sweep/radix_sort.h"
#include "core/sweep/slab_grid.h"
#include "core/sweep/succ_tree.h"
#include "core/sweep/sweep.h"
#include "sap_broadphase/core/config.h"
#include "sap_broadphase/core/frame_report.h"

namespace sap_broadphase {

class SweepAndPrune {
 public:
  explicit SweepAndPrune(const BroadphaseConfig& inConfig);

  /// Every overlapping, filter-allowed pair of inBoxes into outPairs, in canonical order.
  /// inPath is FramePath::kSequential (Algorithm 1) or kParallel (Algorithms 2-4). Fills the
  /// report's sweep phases, dispersions, axes and slabs. ioSpread is the spread of inBoxes,
  /// which the key origins and the slabs are placed from. A parallel sweep runs on the scope's
  /// threads (passThreads()), a sequential one on one of them.
  void run(const BoxColumns& inBoxes, FrameSpread& ioSpread, FramePath inPath,
           FrameReport& ioReport, PairList& outPairs);
  /// The sweep axes in force (§5 may have swapped them).
  int primaryAxis() const { return primary_axis_; }
  int secondaryAxis() const { return secondary_axis_; }
  /// Forgets temporal state: the next sort initialises B from the span.
  void forgetCoherence();
  /// Gives back every per-frame buffer (they grow again on the next frame).
  void releaseBuffers();
  /// Boxes the buffers were last sized for.
  std::size_t capacityBoxes() const { return ranges_.of_object.capacity(); }

 private:
  void placeKeyOrigins(FrameSpread& ioSpread);
  double sortAxis(const BoxColumns& inBoxes, int inAxis, FrameReport& ioReport);
  void gatherByRank(const BoxColumns& inBoxes, FrameSpread& ioSpread);
  void pair(const BoxColumns& inBoxes, FramePath inPath, FrameReport& ioReport);
  void decideAxes(bool inWarm, FrameReport& ioReport);

  const bool exact_final_test_;
  const std::size_t max_pairs_;
  const bool axis_swapping_;
  const double axis_swap_threshold_;
  const int third_axis_slabs_;
  int primary_axis_;
  int secondary_axis_;
  AxisBounds bounds_[3];
  KeyOrigin key_origin_;
  bool origin_placed_[3] = {false, false, false};
  PartitionedSorter sorter_;
  // 4n words: packed (key, index) items and the sort's scratch while sorting, then the
  // secondary stream (2 words per endpoint) while pairing.
  Buffer<uint64_t> endpoint_words_;
  Buffer<uint32_t> sweep_order_;  // 2n endpoint indexes: primary order, then secondary
  CandidateRanges ranges_;
  Buffer<RankedKeys> ranked_keys_;
  Buffer<RankedFilter> ranked_filters_;
  Buffer<RankedSlabs> ranked_slabs_;
  SlabGrid slab_grid_;
  SweepWorkspace workspace_;
  SuccTree sequential_tree_;
  std::vector<PairChunks> pairs_per_thread_;
  PairSortScratch pair_scratch_;
};

}  // namespace sap_broadphase
