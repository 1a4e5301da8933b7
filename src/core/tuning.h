// The engine's tuning constants, each with the reason for its value. None of them affects
// which pairs are reported, only how fast they are found and how much memory is kept.
#pragma once

#include <cstddef>

namespace sap_broadphase::tuning {

// ---- Sweep (Algorithms 2-4) ----

/// Sort partitions (m of Algorithm 2). More partitions than threads keeps each one
/// cache-sized and gives the dispersion D a grain fine enough to notice clustering (§5);
/// they are handed out to threads dynamically.
constexpr int kSortPartitions = 16;
/// Below this many endpoints one partition is cheaper than bucketing into m of them.
constexpr std::size_t kMinPartitionedEndpoints = 8192;

// ---- Large-world coordinates (sort keys relative to the frame) ----

/// The keys are float32 of (coordinate - origin). The origin is 0 (the keys of the
/// coordinates themselves) unless the frame's centre lies more than this many half-spans from
/// 0: there keys of the coordinates would be at least that many times coarser than keys
/// relative to the centre (UTM and ECEF coordinates, for example).
constexpr double kFarFromOriginInSpans = 64.0;
/// The origin of an axis is kept from frame The origin of an axis is kept from frame
/// to frame, so that the partition bounds B stay valid (temporal coherence), until the
/// frame's centre moved by more than this fraction of its span: then precision near the
/// boxes would start to suffer and the origin is re-centred.
constexpr double kOriginDriftInSpans = 0.125;

// ---- Frame history and the plan ----

/// Frames that must each be at most a quarter of the largest recent frame before the
/// per-frame buffers are given back (a burst of large frames should not keep its memory
/// for a node that runs for days; an occasional large frame should not trash the buffers).
constexpr int kShrinkAfterSmallFrames = 64;
/// A frame this many times smaller than the buffers' capacity counts as small.
constexpr std::size_t kShrinkRatio = 4;

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
/// Frames whose largest displacement sets the motion v: the maximum over a short window,
/// since one box leaving its skin forces a new sweep.
constexpr int kMotionWindow = 4;
/// Smallest frame for which a skin is considered: below it a sweep costs microseconds.
constexpr std::size_t kMinSkinBoxes = 1024;
/// Until a pass has been measured: nanoseconds per kept candidate and per box (containment
/// check and gather) of a pass on one thread, conservative.
constexpr double kInitialNsPerCandidate = 10.0;
constexpr double kInitialNsPerBox = 5.0;
/// Weight of the newest measurement in the running cost averages.
constexpr double kCostSmoothing = 0.5;

}  // namespace sap_broadphase::tuning
