#include "core/strategies/skin_reuse.h"

#include <algorithm>
#include <iterator>
#include <utility>

#include "core/assert.h"
#include "core/sweep/axis_spread.h"
#include "core/runner/phase_timer.h"

namespace sap_broadphase {
namespace {

double smoothed(double inAverage, double inSample) {
  return inAverage > 0.0 ? inAverage + tuning::kCostSmoothing * (inSample - inAverage) : inSample;
}

// Mean finite box extent and the span of the finite bounds on each axis (the skin cost
// model's picture of the frame).
void measureExtents(FrameSpread& ioSpread, int inThreads, SkinCosts& ioCosts) {
  for (int axis = 0; axis < 3; ++axis) {
    const AxisSpread& spread = ioSpread.axis(axis, inThreads);
    ioCosts.mean_extent[axis] = spread.meanExtent();
    ioCosts.span[axis] = spread.span();
  }
}

}  // namespace

void SkinReuse::startFrame(const FrameDelta& inDelta) {
  times_ = WorkTimes();
  over_budget_frame_ = false;
  if (!inDelta.sameIds()) {
    std::fill(std::begin(recent_motion_), std::end(recent_motion_), 0.0);
    return;
  }
  recent_motion_[motion_slot_] = inDelta.max_displacement;
  motion_slot_ = (motion_slot_ + 1) % tuning::kMotionWindow;
}

double SkinReuse::recentMotion() const {
  return *std::max_element(std::begin(recent_motion_), std::end(recent_motion_));
}

bool SkinReuse::coversFrame(const BoxColumns& inSwept, int inThreads, FrameReport& ioReport) {
  times_.ms_pass = 0.0;  // the pass that answers the frame starts with this gather
  PhaseTimer timer(ioReport.ms_skin);
  PhaseTimer pass_timer(times_.ms_pass);
  return kept_.gather(inSwept, inThreads);
}

void SkinReuse::answerFromCandidates(int inThreads, FrameReport& ioReport, PairList& outPairs) {
  PhaseTimer timer(ioReport.ms_skin);
  PhaseTimer pass_timer(times_.ms_pass);
  ioReport.skin_candidates = kept_.candidates();
  kept_.collectGathered(inThreads, outPairs);
}

const BoxColumns& SkinReuse::grow(const BoxColumns& inSwept, double inSkin, int inThreads,
                                  FrameReport& ioReport) {
  PhaseTimer timer(ioReport.ms_skin);
  PhaseTimer grow_timer(times_.ms_grow);
  skin_ = inSkin;
  if (inSkin >= over_budget_skin_ && inSwept.size() == over_budget_boxes_) {
    // This skin already found more candidates than the budget at this size: sweep the boxes
    // as they are (kept candidates of skin 0, for an unchanged frame) instead.
    skin_ = 0.0;
    over_budget_frame_ = true;
    ioReport.skin = 0.0;
    ioReport.skin_choice = SkinChoice::kOverBudget;
  }
  return kept_.inflate(inSwept, skin_, inThreads);
}

void SkinReuse::keepAndAnswer(const BoxColumns& inSwept, int inThreads, FrameReport& ioReport,
                              PairList& ioPairs) {
  {
    PhaseTimer timer(ioReport.ms_skin);
    PhaseTimer keep_timer(times_.ms_keep);
    if (ioPairs.size() > keptCandidateBudget(inSwept.size())) {
      keepNoCandidates(inSwept, ioReport, ioPairs);
      return;
    }
    kept_.adopt(inSwept, std::move(ioPairs));  // taken, not copied: ioPairs is rewritten below
  }
  // Every box lies inside its own grown box: the pass that answers the frame always runs.
  const bool covered = coversFrame(inSwept, inThreads, ioReport);
  SAP_ASSERT(covered, "a box outside the skin it was just grown by");
  static_cast<void>(covered);
  answerFromCandidates(inThreads, ioReport, ioPairs);
}

// Over the budget: the grown sweep's candidates answer this frame once, tested exactly, and
// are not kept; their memory goes back at once.
void SkinReuse::keepNoCandidates(const BoxColumns& inSwept, FrameReport& ioReport,
                                 PairList& ioPairs) {
  over_budget_skin_ = skin_;
  over_budget_boxes_ = inSwept.size();
  over_budget_frame_ = true;
  kept_ = SkinList();  // gives back the last candidates' memory too
  SkinList::keepOverlapping(inSwept, ioPairs);
  ioPairs.shrink_to_fit();
  ioReport.skin = 0.0;
  ioReport.skin_candidates = 0;
  ioReport.skin_choice = SkinChoice::kOverBudget;
}

// A grown sweep's frame holds four kinds of work: growing the boxes, the sweep itself, keeping
// its candidates and the pass that answers the frame; each is learnt as its own cost
// (SkinCosts). The sweep's own phases (keys, sorts, candidates, pairing, output) hold only the
// sweep: the skin's work is in the report's ms_skin.
void SkinReuse::learn(const FramePlan& inPlan, FrameSpread& ioSwept, std::size_t inSweepPairs,
                      const FrameReport& inReport) {
  const BoxColumns& swept = ioSwept.boxes();
  const double boxes = static_cast<double>(swept.size());
  const bool grown = findsAllPairs(inPlan.path) && inPlan.sweep_skin > 0.0;
  if (findsAllPairs(inPlan.path) && swept.size() >= tuning::kMinSkinBoxes) {
    const double candidates = static_cast<double>(grown ? kept_.candidates() : inSweepPairs);
    // The small-frame kernel's phases are one (ms_pairing): its cost is charged per box and
    // candidate, as the cells' sweeps it is made of cost.
    const double ms_sweep_per_box = inReport.ms_keys + inReport.ms_sort + inReport.ms_candidates;
    const double ms_sweep_per_item = inReport.ms_pairing + inReport.ms_output;
    costs_.sweep_ns_per_box = ms_sweep_per_box * 1e6 / boxes;
    costs_.pairing_ns_per_item = ms_sweep_per_item * 1e6 / (boxes + candidates);
    costs_.reference_boxes = swept.size();
    costs_.reference_candidates = candidates;
    costs_.reference_skin = inPlan.sweep_skin;
    measureExtents(ioSwept, inPlan.threads, costs_);
    if (grown) {
      costs_.grow_ns_per_box = smoothed(costs_.grow_ns_per_box, times_.ms_grow * 1e6 / boxes);
      costs_.keep_ns_per_candidate =
          smoothed(costs_.keep_ns_per_candidate, times_.ms_keep * 1e6 / std::max(1.0, candidates));
    }
  }
  const bool answered_by_pass = inPlan.path == FramePath::kSkin || grown;
  if (answered_by_pass && kept_.candidates() > 0) learnPassCosts(times_.ms_pass, boxes);
}

// The whole pass is charged to its candidates and boxes in the proportion of the initial
// estimates; what matters to the model is the pass's total at this size.
void SkinReuse::learnPassCosts(double inMilliseconds, double inBoxes) {
  const double estimate = tuning::kInitialNsPerBox * inBoxes +
                          tuning::kInitialNsPerCandidate * static_cast<double>(kept_.candidates());
  const double scale = inMilliseconds * 1e6 / estimate;
  costs_.pass_ns_per_box = smoothed(costs_.pass_ns_per_box, tuning::kInitialNsPerBox * scale);
  costs_.pass_ns_per_candidate =
      smoothed(costs_.pass_ns_per_candidate, tuning::kInitialNsPerCandidate * scale);
}

}  // namespace sap_broadphase
