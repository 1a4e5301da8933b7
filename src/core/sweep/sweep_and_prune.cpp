#include "core/sweep/sweep_and_prune.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/assert.h"
#include "core/runner/buffers.h"
#include "core/runner/phase_timer.h"
#include "core/runner/work_units.h"
#include "core/sweep/axis_policy.h"
#include "core/sweep/axis_spread.h"
#include "core/sweep/sort_keys.h"
#include "core/tuning.h"

namespace sap_broadphase {

SweepAndPrune::SweepAndPrune(const BroadphaseConfig& inConfig)
    : exact_final_test_(inConfig.exact_final_test),
      max_pairs_(inConfig.max_pairs),
      axis_swapping_(inConfig.axis_swapping),
      axis_swap_threshold_(inConfig.axis_swap_threshold),
      third_axis_slabs_(inConfig.third_axis_slabs),
      primary_axis_(inConfig.primary_axis),
      secondary_axis_(inConfig.secondary_axis) {}

void SweepAndPrune::forgetCoherence() {
  for (int axis = 0; axis < 3; ++axis) {
    bounds_[axis].from_previous_frame = false;
    origin_placed_[axis] = false;
  }
}

void SweepAndPrune::releaseBuffers() {
  Buffer<uint64_t>().swap(endpoint_words_);
  Buffer<uint32_t>().swap(sweep_order_);
  ranges_ = CandidateRanges();
  Buffer<RankedKeys>().swap(ranked_keys_);
  Buffer<RankedFilter>().swap(ranked_filters_);
  Buffer<RankedSlabs>().swap(ranked_slabs_);
  workspace_ = SweepWorkspace();
  sequential_tree_ = SuccTree();
  pairs_per_thread_.clear();
  pair_scratch_ = PairSortScratch();
  sorter_ = PartitionedSorter();
}

// A placed origin is kept while the frame stays around it (a moved origin shifts every key,
// and B with them).
void SweepAndPrune::placeKeyOrigins(FrameSpread& ioSpread) {
  for (int axis = 0; axis < 3; ++axis) {
    const AxisSpread& spread = ioSpread.axis(axis);
    const double origin = axisKeyOrigin(spread);
    const double span = spread.hasSpan() ? spread.highest / 2 - spread.lowest / 2 : 0.0;  // half
    const double drift = std::fabs(origin - key_origin_.origin[axis]);
    if (origin_placed_[axis] && drift <= tuning::kOriginDriftInSpans * 2 * span) continue;
    if (key_origin_.origin[axis] != origin)
      bounds_[axis].from_previous_frame = false;  // B was measured in the old keys
    key_origin_.origin[axis] = origin;
    origin_placed_[axis] = true;
  }
}

// Keys of one axis (lows at i, highs at i + n), packed with their indexes, then Algorithm 2.
// Returns D.
double SweepAndPrune::sortAxis(const BoxColumns& inBoxes, int inAxis, FrameReport& ioReport) {
  const uint32_t n = static_cast<uint32_t>(inBoxes.size());
  const std::size_t endpoints = 2 * std::size_t{n};
  {
    PhaseTimer timer(ioReport.ms_keys);
    const double* low = inBoxes.lo[inAxis].data();
    const double* high = inBoxes.hi[inAxis].data();
    resizeDiscarding(endpoint_words_, 2 * endpoints);
    resizeDiscarding(sweep_order_, endpoints);
    uint64_t* packed = endpoint_words_.data();
    const KeyOrigin origin = key_origin_;
    runOverItems(WorkUnits{n}, [&](std::size_t inBegin, std::size_t inEnd) {
      for (auto i = static_cast<uint32_t>(inBegin); i < inEnd; ++i) {
        packed[i] = packKeyIndex(origin.low(inAxis, low[i]), i);
        packed[i + n] = packKeyIndex(origin.high(inAxis, high[i]), i + n);
      }
    });
  }
  PhaseTimer timer(ioReport.ms_sort);
  uint64_t* packed = endpoint_words_.data();
  const int partitions =
      endpoints >= tuning::kMinPartitionedEndpoints ? tuning::kSortPartitions : 1;
  return sorter_.sortPacked(packed, packed + endpoints, static_cast<uint32_t>(endpoints),
                            partitions, bounds_[inAxis], sweep_order_.data());
}

// Box data in primary-rank order, so a candidate range is a contiguous stretch of memory.
void SweepAndPrune::gatherByRank(const BoxColumns& inBoxes, FrameSpread& ioSpread) {
  const uint32_t n = static_cast<uint32_t>(inBoxes.size());
  const bool filtered = inBoxes.hasFilters();
  resizeDiscarding(ranked_keys_, n);
  resizeDiscarding(ranked_filters_, filtered ? n : 0);
  const int third_axis = unusedAxis(primary_axis_, secondary_axis_);
  slab_grid_ = chooseSlabGrid(ioSpread, third_axis, third_axis_slabs_);
  const bool slabbed = slab_grid_.count > 1;
  resizeDiscarding(ranked_slabs_, slabbed ? n : 0);
  const double* third_low = inBoxes.lo[third_axis].data();
  const double* third_high = inBoxes.hi[third_axis].data();
  const KeyOrigin origin = key_origin_;
  // Reads the boxes in input order (sequential streams of the SoA arrays) and writes each one's
  // record at its rank: one scattered write a box instead of six scattered reads.
  const RankRange* ranges_of_object = ranges_.of_object.data();
  runOverItems(WorkUnits{n}, [&](std::size_t inBegin, std::size_t inEnd) {
    for (auto i = static_cast<uint32_t>(inBegin); i < inEnd; ++i) {
      const uint32_t rank = ranges_of_object[i].rank;
      RankedKeys& keys = ranked_keys_[rank];
      for (int axis = 0; axis < 3; ++axis) {
        keys.lo[axis] = origin.low(axis, inBoxes.lo[axis][i]);
        keys.hi[axis] = origin.high(axis, inBoxes.hi[axis][i]);
      }
      SAP_ASSERT(keys.lo[0] <= keys.hi[0] && keys.lo[1] <= keys.hi[1] && keys.lo[2] <= keys.hi[2],
                 "a key record with lo > hi (keys must round outward)");
      if (slabbed)
        ranked_slabs_[rank] = {static_cast<uint8_t>(slab_grid_.slabOf(third_low[i])),
                               static_cast<uint8_t>(slab_grid_.slabOf(third_high[i]))};
      if (filtered) ranked_filters_[rank] = {inBoxes.group(i), inBoxes.mask(i)};
    }
  });
}

void SweepAndPrune::pair(const BoxColumns& inBoxes, FramePath inPath, FrameReport& ioReport) {
  const uint32_t n = static_cast<uint32_t>(inBoxes.size());
  PairingInput input;
  input.secondary_order = sweep_order_.data();
  input.ranges = ranges_.of_object.data();
  input.stream_scratch = endpoint_words_.data();  // the sort's words are free by now
  input.objects = n;
  input.object_of_rank = ranges_.object_of_rank.data();
  input.keys = ranked_keys_.data();
  input.boxes = exact_final_test_ ? &inBoxes : nullptr;
  input.filters = ranked_filters_.empty() ? nullptr : ranked_filters_.data();
  input.ids = inBoxes.ids.data();
  input.slabs = ranked_slabs_.empty() ? nullptr : ranked_slabs_.data();
  input.slab_count = slab_grid_.count;
  ioReport.slabs = slab_grid_.count;
  // Past max_pairs the pairing threads throw TooManyPairs (the engine then gives back these
  // buffers: the trees are left holding boxes).
  PairBudget budget(max_pairs_);
  const BudgetScope budget_scope(pairs_per_thread_);
  input.pair_budget = &budget;
  if (inPath == FramePath::kSequential) {
    pairs_per_thread_.resize(1);
    pairs_per_thread_[0].clear();
    pairSequential(input, workspace_, pairs_per_thread_[0]);
  } else {
    pairParallel(input, workspace_, pairs_per_thread_);
  }
}

void SweepAndPrune::run(const BoxColumns& inBoxes, FrameSpread& ioSpread, FramePath inPath,
                        FrameReport& ioReport, PairList& outPairs) {
  SAP_ASSERT(&ioSpread.boxes() == &inBoxes, "the sweep reads the spread of other boxes");
  const uint32_t n = static_cast<uint32_t>(inBoxes.size());
  ioReport.primary_axis = primary_axis_;
  ioReport.secondary_axis = secondary_axis_;
  if (n < 2) {
    outPairs.clear();
    return;
  }
  // A sequential sweep (Algorithm 1) keeps its passes to one thread; a parallel one runs on the
  // scope's.
  const NarrowedScope sweep_threads(inPath == FramePath::kParallel ? passThreads() : 1);
  {
    PhaseTimer timer(ioReport.ms_keys);
    placeKeyOrigins(ioSpread);
  }
  const bool warm =
      bounds_[primary_axis_].from_previous_frame && bounds_[secondary_axis_].from_previous_frame;

  // The primary order is consumed by candidate generation before the secondary axis is
  // sorted, so both orders share one buffer (sweep_order_).
  ioReport.dispersion_primary = sortAxis(inBoxes, primary_axis_, ioReport);
  {
    PhaseTimer timer(ioReport.ms_candidates);
    if (inPath == FramePath::kParallel)
      computeCandidatesParallel(sweep_order_.data(), n, workspace_, ranges_);
    else
      computeCandidatesSequential(sweep_order_.data(), n, sequential_tree_, ranges_);
  }
  ioReport.dispersion_secondary = sortAxis(inBoxes, secondary_axis_, ioReport);
  {
    PhaseTimer timer(ioReport.ms_pairing);
    gatherByRank(inBoxes, ioSpread);
    pair(inBoxes, inPath, ioReport);
  }
  {
    PhaseTimer timer(ioReport.ms_output);
    // Each thread's pairs are disjoint from the others': merging them is the whole set. The
    // sweep order is dead by now: the sort borrows its memory for its histogram.
    std::swap(sweep_order_, pair_scratch_.offsets);
    sortPairsCanonical(pairs_per_thread_, outPairs, pair_scratch_);
    std::swap(sweep_order_, pair_scratch_.offsets);
  }
  decideAxes(warm && axis_swapping_ && 2 * std::size_t{n} >= tuning::kMinPartitionedEndpoints,
             ioReport);
}

void SweepAndPrune::decideAxes(bool inWarm, FrameReport& ioReport) {
  const AxisDecision decision =
      chooseAxes(primary_axis_, secondary_axis_, ioReport.dispersion_primary,
                 ioReport.dispersion_secondary, inWarm, axis_swap_threshold_);
  ioReport.axes_swapped = decision.swapped;
  if (!decision.swapped) return;
  const int incoming = decision.primary != primary_axis_ ? decision.primary : decision.secondary;
  bounds_[incoming].from_previous_frame = false;  // re-initialise B from the new axis's span
  primary_axis_ = decision.primary;
  secondary_axis_ = decision.secondary;
}

}  // namespace sap_broadphase
