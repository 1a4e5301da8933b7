#include "core/frame/frame_plan.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "core/tuning.h"

namespace sap_broadphase {
namespace {

// Candidates a sweep of inBoxes boxes grown by inSkin would find if the boxes were spread
// uniformly over the frame: two boxes are candidates when their grown intervals overlap on
// every axis, on one axis with probability (sum of extents + skin) / span.
double uniformCandidates(const SkinCosts& inCosts, double inBoxes, double inSkin) {
  double pairs = inBoxes * (inBoxes - 1.0) / 2.0;
  for (int axis = 0; axis < 3; ++axis) {
    const double reach = 2.0 * inCosts.mean_extent[axis] + inSkin;
    const double span = inCosts.span[axis];
    pairs *= span > 0.0 ? std::min(1.0, reach / span) : 1.0;
  }
  return pairs;
}

// Expected candidates at skin inSkin: the uniform estimate, scaled up by how much more the
// last sweep found than that estimate at its own skin (clustered scenes), never down (a
// sweep that found no pair says little about how many a grown one would find).
double expectedCandidates(const SkinCosts& inCosts, double inBoxes, double inSkin) {
  const double reference_boxes = static_cast<double>(inCosts.reference_boxes);
  const double reference_estimate =
      uniformCandidates(inCosts, reference_boxes, inCosts.reference_skin);
  const double clustering = reference_estimate > 0.0
                                ? std::max(1.0, inCosts.reference_candidates / reference_estimate)
                                : 1.0;
  return uniformCandidates(inCosts, inBoxes, inSkin) * clustering;
}

// Expected nanoseconds of a sweep of inBoxes boxes grown by inSkin, and the candidates found.
double sweepNs(const SkinCosts& inCosts, double inBoxes, double inSkin, double& outCandidates) {
  outCandidates = expectedCandidates(inCosts, inBoxes, inSkin);
  return inCosts.sweep_ns_per_box * inBoxes +
         inCosts.pairing_ns_per_item * (inBoxes + outCandidates);
}

// Expected nanoseconds a frame of a cycle at skin inSkin: one sweep of the grown boxes that
// keeps its candidates, then kept-candidate passes until a box has moved half the skin (the
// sweep frame passes too).
double cycleNsPerFrame(const SkinCosts& inCosts, double inBoxes, double inSkin, double inMotion) {
  double candidates = 0.0;
  const double sweep_ns = sweepNs(inCosts, inBoxes, inSkin, candidates) +
                          inCosts.grow_ns_per_box * inBoxes +
                          inCosts.keep_ns_per_candidate * candidates;
  const double pass_ns =
      inCosts.pass_ns_per_box * inBoxes + inCosts.pass_ns_per_candidate * candidates;
  const double frames = 1.0 + std::floor(inSkin / (2.0 * inMotion));
  return (sweep_ns + frames * pass_ns) / frames;
}

// The automatic skin of a frame found from scratch (no skin on a first frame or one of other
// ids: nothing is known of their motion).
void chooseAutomaticSkin(const PlanInputs& inInputs, FramePlan& ioPlan) {
  if (inInputs.delta.relation == FrameRelation::kFirst) {
    ioPlan.skin_choice = SkinChoice::kFirstFrame;
  } else if (!inInputs.delta.sameIds()) {
    ioPlan.skin_choice = SkinChoice::kIdsChanged;
  } else if (!inInputs.skin_audit_allows) {
    ioPlan.skin_choice = SkinChoice::kNotWorthIt;
  } else {
    ioPlan.sweep_skin =
        chooseSkin(inInputs.motion, inInputs.boxes, inInputs.costs, ioPlan.skin_choice);
  }
  ioPlan.skin = ioPlan.sweep_skin;
}

}  // namespace

FramePath sweepPath(const BroadphaseConfig& inConfig, std::size_t inBoxes, int inThreads) {
  switch (inConfig.method) {
    case Method::kParallel:
      return FramePath::kParallel;
    case Method::kSequential:
    case Method::kBruteForce:
      return FramePath::kSequential;
    case Method::kAuto:
      break;
  }
  return inThreads == 1 || inBoxes < inConfig.parallel_min_boxes ? FramePath::kSequential
                                                                 : FramePath::kParallel;
}

double chooseSkin(double inMotion, std::size_t inBoxes, const SkinCosts& inCosts,
                  SkinChoice& outChoice) {
  outChoice = SkinChoice::kNotWorthIt;
  if (inBoxes < tuning::kMinSkinBoxes || inCosts.reference_boxes == 0 || !(inMotion > 0.0))
    return 0.0;
  outChoice = SkinChoice::kTooFast;
  if (!std::isfinite(inMotion)) return 0.0;
  SkinCosts costs = inCosts;
  if (costs.pass_ns_per_box <= 0.0) {
    costs.pass_ns_per_box = tuning::kInitialNsPerBox;
    costs.pass_ns_per_candidate = tuning::kInitialNsPerCandidate;
  }
  if (costs.grow_ns_per_box <= 0.0) {
    costs.grow_ns_per_box = tuning::kInitialGrowNsPerBox;
    costs.keep_ns_per_candidate = tuning::kInitialKeepNsPerCandidate;
  }
  const double boxes = static_cast<double>(inBoxes);
  double plain_candidates = 0.0;
  const double plain_ns = tuning::kSkinWorthIt * sweepNs(costs, boxes, 0.0, plain_candidates);
  const double widest_box =
      *std::max_element(std::begin(inCosts.mean_extent), std::end(inCosts.mean_extent));
  // The expected cost of each skin tried (0: beyond the largest skin considered).
  double skin_ns[std::size(tuning::kSkinInMotions)] = {};
  double cheapest_ns = plain_ns;
  for (std::size_t k = 0; k < std::size(tuning::kSkinInMotions); ++k) {
    const double skin = tuning::kSkinInMotions[k] * inMotion;
    if (skin > tuning::kMaxSkinInExtents * widest_box) break;
    skin_ns[k] = cycleNsPerFrame(costs, boxes, skin, inMotion);
    cheapest_ns = std::min(cheapest_ns, skin_ns[k]);
  }
  if (!(cheapest_ns < plain_ns)) return 0.0;
  // Near its minimum the cost of a cycle is flat in the skin, while the model's error grows
  // with the candidates (a wider skin's candidates outgrow the caches the measured pass ran
  // in): of the skins within a small margin of the cheapest, the smallest is taken.
  for (std::size_t k = 0; k < std::size(tuning::kSkinInMotions); ++k) {
    if (skin_ns[k] > 0.0 && skin_ns[k] <= tuning::kSkinCostMargin * cheapest_ns &&
        skin_ns[k] < plain_ns) {
      outChoice = SkinChoice::kChosen;
      return tuning::kSkinInMotions[k] * inMotion;
    }
  }
  return 0.0;
}

bool takesSmallFrameKernel(const BroadphaseConfig& inConfig, std::size_t inBoxes, int inThreads) {
  const bool skin_fixed = inConfig.skin && *inConfig.skin > 0.0;
  return inConfig.method == Method::kAuto && !skin_fixed &&
         (inBoxes < inConfig.parallel_min_boxes || inThreads <= tuning::kKernelMostThreads);
}

int frameThreads(const BroadphaseConfig& inConfig, std::size_t inBoxes, int inThreads) {
  const bool small = inConfig.method == Method::kAuto && inBoxes < inConfig.parallel_min_boxes;
  return small && takesSmallFrameKernel(inConfig, inBoxes, inThreads) ? 1 : inThreads;
}

bool reusesLastPairs(const BroadphaseConfig& inConfig, const FrameDelta& inDelta,
                     bool inLastPairsValid) {
  return inConfig.reuse_unchanged_frames && inDelta.relation == FrameRelation::kIdentical &&
         inLastPairsValid;
}

bool planConsidersKeptCandidates(const PlanInputs& inInputs) {
  const BroadphaseConfig& config = *inInputs.config;
  const bool skin_off = config.skin && *config.skin == 0.0;
  const bool skin_fixed = config.skin && *config.skin > 0.0;
  return inInputs.boxes >= 2 && (skin_fixed || inInputs.skin_audit_allows) &&
         config.method != Method::kBruteForce &&
         !reusesLastPairs(config, inInputs.delta, inInputs.last_pairs_valid) && !skin_off &&
         inInputs.kept_candidates && inInputs.delta.sameIds() && !inInputs.delta.filters_changed;
}

FramePlan planFrame(const PlanInputs& inInputs) {
  const BroadphaseConfig& config = *inInputs.config;
  const FrameDelta& delta = inInputs.delta;
  FramePlan plan;
  const bool skin_off = config.skin && *config.skin == 0.0;
  const bool skin_fixed = config.skin && *config.skin > 0.0;
  plan.skin_choice = skin_off ? SkinChoice::kOff : SkinChoice::kNotWorthIt;
  if (inInputs.boxes < 2) return plan;  // kEmpty
  if (config.method == Method::kBruteForce) {
    plan.path = FramePath::kBruteForce;
    return plan;
  }
  if (reusesLastPairs(config, delta, inInputs.last_pairs_valid)) {
    plan.path = FramePath::kReused;
    if (inInputs.kept_candidates) plan.skin = inInputs.kept_skin;
    plan.skin_choice = skin_fixed ? SkinChoice::kFixed : plan.skin_choice;
    return plan;
  }
  plan.threads = inInputs.threads;
  if (planConsidersKeptCandidates(inInputs) && inInputs.kept_covers) {
    plan.path = FramePath::kSkin;
    plan.skin = inInputs.kept_skin;
    plan.skin_choice = skin_fixed ? SkinChoice::kFixed : SkinChoice::kKept;
    return plan;
  }
  if (takesSmallFrameKernel(config, inInputs.boxes, inInputs.threads)) {
    // The small-frame kernel, on the frame's threads (one below the cut-off); grown by the
    // automatic skin when its cycle pays, as a sweep is: what the paper's coherence (§4.2) is
    // to the sweep, the kept candidates are to the kernel, which keeps nothing of its own.
    plan.path = FramePath::kSmallFrame;
    if (!skin_off) chooseAutomaticSkin(inInputs, plan);
    return plan;
  }
  plan.path = sweepPath(config, inInputs.boxes, inInputs.threads);
  if (plan.path == FramePath::kSequential) plan.threads = 1;
  if (skin_off) return plan;
  if (skin_fixed) {
    plan.sweep_skin = plan.skin = *config.skin;
    plan.skin_choice = SkinChoice::kFixed;
  } else {
    chooseAutomaticSkin(inInputs, plan);
  }
  // The kept-candidate passes of a grown sweep run on every thread.
  if (plan.sweep_skin > 0.0) plan.threads = inInputs.threads;
  return plan;
}

}  // namespace sap_broadphase
