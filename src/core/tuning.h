// The engine's tuning constants, each with the reason for its value. None of them affects
// which pairs are reported, only how fast they are found and how much memory is kept.
#pragma once

#include <cstddef>
#include <cstdint>

namespace sap_broadphase::tuning {

// ---- Sweep (Algorithms 2-4) ----

/// Sort partitions (m of Algorithm 2). More partitions than threads keeps each one
/// cache-sized and gives the dispersion D a grain fine enough to notice clustering (§5);
/// they are handed out to threads dynamically.
constexpr int kSortPartitions = 16;
/// Below this many endpoints one partition is cheaper than bucketing into m of them.
constexpr std::size_t kMinPartitionedEndpoints = 8192;

// ---- Third-axis slab active lists (slab_grid.h) ----

/// Below this many boxes one active list is as fast as any split.
constexpr std::size_t kMinBoxesForSlabs = 2048;
/// Slab width in mean box extents: wider slabs mean more candidates per query, narrower ones
/// mean boxes sit in more trees.
constexpr double kSlabWidthInExtents = 2.0;

// ---- Static index: resting boxes and declared scenery (static_index.h, static_split.h) ----

/// Cell edge in mean box extents. At one extent a box covers about 2^3 cells and a cell holds
/// about density * 8 boxes; the cap below usually decides instead.
constexpr double kCellInExtents = 1.0;
/// Most cells per indexed box: bounds the offsets array (8 bytes a cell) and empty-cell visits.
constexpr double kCellsPerBox = 1.0;
/// A box covering more cells than this goes to the large list: listing it in every cell would
/// cost more memory and cell visits than testing it against each query.
constexpr uint64_t kMaxCellsPerBox = 64;

/// Most distinct group/mask classes looked at among the unchanged boxes.
constexpr std::size_t kMaxFilterClasses = 64;

// ---- Large-world coordinates (sort keys relative to the frame) ----

/// The keys are float32 of (coordinate - origin). The origin is 0 (the keys of the
/// coordinates themselves) unless the frame's centre lies more than this many half-spans from
/// 0: there keys of the coordinates would be at least that many times coarser than keys
/// relative to the centre (UTM and ECEF coordinates, for example).
constexpr double kFarFromOriginInSpans = 64.0;
/// The origin of an axis is kept from frame to frame, so that the partition bounds B stay valid
/// (temporal coherence), until the frame's centre moved by more than this fraction of its span:
/// then precision near the boxes would start to suffer and the origin is re-centred.
constexpr double kOriginDriftInSpans = 0.125;

// ---- Frame history and the plan ----

// When buffers are given back after a burst of large frames: memory_policy.h.

// ---- Automatic skin (kept candidates, skin_list.h) ----

/// Skins tried, in multiples of the measured per-frame motion: a skin s lasts about
/// s / (2 v) frames at motion v. The cost model (frame_plan.cpp) picks the cheapest.
constexpr double kSkinInMotions[] = {2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64};
/// Largest skin, in mean box extents: beyond it the candidates grow faster than any cost
/// model of a uniform scene predicts in a clustered one (a guard, not a tuning).
constexpr double kMaxSkinInExtents = 2.0;
/// A skin is only used when the model expects it to cost at most this fraction of a plain
/// sweep per frame: a margin for the model's error, so that fast motion turns skin off.
constexpr double kSkinWorthIt = 0.8;
/// Skins whose expected cost is within this factor of the cheapest count as equally cheap;
/// the smallest of them is used (its candidates are the fewest, its prediction the surest).
constexpr double kSkinCostMargin = 1.1;
/// Frames whose largest displacement sets the motion v: the maximum over a short window,
/// since one box leaving its skin forces a new sweep.
constexpr int kMotionWindow = 4;
/// Smallest frame for which a skin is considered: below it a sweep costs microseconds.
constexpr std::size_t kMinSkinBoxes = 1024;
/// Until a pass has been measured: nanoseconds per kept candidate and per box (containment
/// check and gather) of a pass on one thread, conservative.
constexpr double kInitialNsPerCandidate = 10.0;
constexpr double kInitialNsPerBox = 5.0;
/// Until a grown sweep has been measured: nanoseconds per box to grow the boxes and per
/// candidate to keep the grown sweep's pairs (spatial order, rows), one thread, conservative.
constexpr double kInitialGrowNsPerBox = 10.0;
constexpr double kInitialKeepNsPerCandidate = 30.0;
/// Weight of the newest measurement in the running cost averages.
constexpr double kCostSmoothing = 0.5;

}  // namespace sap_broadphase::tuning
