// The plan of a frame: which work computes it, decided from the configuration, what changed
// since the last frame, the frame's size and the measured costs. A pure function, so every
// choice the engine makes can be tested on its own (test_frame_plan.cpp).
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/frame/frame_history.h"
#include "sap_broadphase/core/config.h"
#include "sap_broadphase/core/frame_report.h"

namespace sap_broadphase {

/// True when inPath is a sweep and prune (Algorithm 1, or Algorithms 2-4).
inline bool isSweep(FramePath inPath) {
  return inPath == FramePath::kSequential || inPath == FramePath::kParallel;
}

/// True when inPath finds the pairs of the whole frame from scratch, so that a skin can grow its
/// boxes and keep what it finds as candidates: a sweep, or the small-frame kernel (which is to
/// small frames what the sweep is to large ones).
inline bool findsAllPairs(FramePath inPath) {
  return isSweep(inPath) || inPath == FramePath::kSmallFrame;
}

/// What earlier frames measured, for choosing a skin. A sweep costs a part per box (keys,
/// sorts, candidate ranges) and a part per box and candidate (pairing, output); the
/// small-frame kernel is charged per box and candidate only (its cells' sweeps); a grown
/// sweep adds the growing and the keeping of its candidates; a kept-candidate pass costs a
/// part per box (containment) and one per candidate (the exact test). Each part is learnt
/// only from the work it describes, so that a grown sweep's extra work is charged to the skin
/// and never to the plain sweep it is compared with.
struct SkinCosts {
  double sweep_ns_per_box = 0.0;     ///< 0: no sweep measured yet
  double pairing_ns_per_item = 0.0;  ///< per box + candidate of that sweep
  double pass_ns_per_box = 0.0;      ///< 0: no pass measured yet
  double pass_ns_per_candidate = 0.0;
  /// What a grown sweep costs beyond the same sweep of plain boxes: growing the boxes (per
  /// box) and keeping its pairs as candidates (per candidate). 0: no grown sweep measured yet.
  double grow_ns_per_box = 0.0;
  double keep_ns_per_candidate = 0.0;
  std::size_t reference_boxes = 0;          ///< boxes of the last sweep
  double reference_candidates = 0.0;        ///< pairs it found (of its grown boxes)
  double reference_skin = 0.0;              ///< its skin
  double mean_extent[3] = {0.0, 0.0, 0.0};  ///< mean finite box extent per axis, then
  double span[3] = {0.0, 0.0, 0.0};         ///< extent of the frame's finite bounds per axis
};

/// Everything the plan depends on.
struct PlanInputs {
  const BroadphaseConfig* config = nullptr;
  FrameDelta delta;
  std::size_t boxes = 0;  ///< boxes that can pair (filtered)
  int threads = 1;        ///< the frame's threads (frameThreads, decided before the loading)
  bool last_pairs_valid = false;  ///< the output still holds the last frame's pairs
  bool kept_candidates = false;   ///< a kept-candidate list exists for these boxes
  bool kept_covers = false;       ///< every box is inside its grown box of that list (asked
                                  ///< only when planConsidersKeptCandidates)
  double kept_skin = 0.0;         ///< the skin of that list
  double motion = 0.0;            ///< per-frame motion: recent largest displacement
  bool skin_audit_allows = true;  ///< the automatic skin has not measured dearer than plain
                                  ///< frames (skin_audit.h)
  SkinCosts costs;
};

/// The plan: the work that computes a frame's pairs (besides the declared scenery, always
/// queried), named as the frame reports it (frame_report.h).
struct FramePlan {
  FramePath path = FramePath::kEmpty;
  int threads = 1;          ///< threads the work uses
  double sweep_skin = 0.0;  ///< a sweep: grow boxes by this skin (0: plain)
  double skin = 0.0;        ///< skin of the candidates used this frame
  SkinChoice skin_choice = SkinChoice::kOff;
};

/// The sequential or parallel sweep for inBoxes boxes (Method::kAuto's rule).
FramePath sweepPath(const BroadphaseConfig& inConfig, std::size_t inBoxes, int inThreads);

/// True when a frame of inBoxes boxes on inThreads threads goes to the small-frame kernel
/// (Method::kAuto, no fixed skin; grown by an automatic skin when one pays) rather than the
/// sweep: below parallel_min_boxes, the one cut-off of Method::kAuto (sweepPath's too), on any
/// thread count; and every frame on up to tuning::kKernelMostThreads threads, where the kernel,
/// its cells run in parallel, beats the paper's sweep at every size measured (tuning.h).
bool takesSmallFrameKernel(const BroadphaseConfig& inConfig, std::size_t inBoxes, int inThreads);

/// The one decision of a frame's threads, made once per frame before anything runs: the
/// frame's loading, its plan's work and the passes after it run on these (the plan may only
/// keep a sequential sweep to one of them), and nothing changes the count afterwards. One for
/// a small frame of Method::kAuto (below parallel_min_boxes: a frame of one work unit, that no
/// other core's availability may delay), the inThreads of the engine's runner otherwise.
int frameThreads(const BroadphaseConfig& inConfig, std::size_t inBoxes, int inThreads);

/// True when the frame's pairs are the last frame's: identical boxes, reuse on, the last
/// pairs still held.
bool reusesLastPairs(const BroadphaseConfig& inConfig, const FrameDelta& inDelta,
                     bool inLastPairsValid);

/// True when the plan would answer the frame from the kept candidates if they cover it: they
/// exist, skin is not off, and no earlier rule (too few boxes, brute force, reuse of the last
/// pairs) decides the frame; ids and filters are unchanged. Only then is coverage worth
/// asking for (SkinReuse::coversFrame), before planFrame.
bool planConsidersKeptCandidates(const PlanInputs& inInputs);

/// Picks the work of a frame.
FramePlan planFrame(const PlanInputs& inInputs);

/// The automatic skin for motion inMotion: the skin whose sweep-then-passes cycle the cost
/// model expects cheapest per frame, or 0 when none beats a plain sweep. outChoice says why.
double chooseSkin(double inMotion, std::size_t inBoxes, const SkinCosts& inCosts,
                  SkinChoice& outChoice);

}  // namespace sap_broadphase
