// Skin reuse as the engine uses it: the kept candidates (skin_list.h), the skin they were
// swept with, the recent motion of the boxes and the learnt costs of plain and grown sweeps
// and of kept-candidate passes, which the plan (frame_plan.h) weighs to choose a skin.
//
// Before a frame is planned, coversFrame() answers whether the boxes about to be swept still
// lie inside the skin of the kept candidates (and gathers their bounds on the way), so that the
// plan is right the first time: a kept-candidate frame is then only the candidates' test.
#pragma once

#include <cstddef>
#include <limits>

#include "core/sweep/axis_spread.h"
#include "core/frame/box_columns.h"
#include "core/frame/frame_history.h"
#include "core/frame/frame_plan.h"
#include "core/strategies/skin_list.h"
#include "core/tuning.h"
#include "sap_broadphase/core/frame_report.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase {

class SkinReuse {
 public:
  /// Starts a frame: its motion joins the recent window (a frame of other ids empties it).
  void startFrame(const FrameDelta& inDelta);

  /// True when the kept candidates answer the frame inSwept: every box inside its grown box
  /// of the last grown sweep (same ids, groups and masks). The frame's bounds are then
  /// gathered for answerFromCandidates().
  bool coversFrame(const BoxColumns& inSwept, int inThreads, FrameReport& ioReport);
  /// FramePath::kSkin, after coversFrame() said yes: the candidates that overlap
  /// now, in canonical order, into outPairs (replaced).
  void answerFromCandidates(int inThreads, FrameReport& ioReport, PairList& outPairs);

  /// A grown sweep, first half: inSwept grown by inSkin / 2 a side, for the sweep to run on
  /// (valid until the next grow()).
  const BoxColumns& grow(const BoxColumns& inSwept, double inSkin, int inThreads,
                         FrameReport& ioReport);
  /// A grown sweep, second half: ioPairs holds the grown boxes' pairs; they become the kept
  /// candidates, and ioPairs the pairs of inSwept among them.
  void keepAndAnswer(const BoxColumns& inSwept, int inThreads, FrameReport& ioReport,
                     PairList& ioPairs);
  /// Forgets the kept candidates (a plain sweep, a small frame or reset()).
  void forget() { kept_.clear(); }

  /// Learns from a frame that ran inPlan on the boxes of ioSwept (their spread, measured here
  /// if the frame has not yet): a sweep's costs per box and per item (from the sweep phases of
  /// inReport, with inSweepPairs its pairs or kept candidates) and the costs of growing,
  /// keeping and passing.
  void learn(const FramePlan& inPlan, FrameSpread& ioSwept, std::size_t inSweepPairs,
             const FrameReport& inReport);

  /// True when this frame's skin went over the kept-candidate budget (keptCandidateBudget):
  /// the frame kept no candidates, or swept its boxes ungrown; its report says kOverBudget.
  bool overBudget() const { return over_budget_frame_; }

  /// What the plan weighs.
  bool hasCandidates() const { return kept_.valid(); }
  double skin() const { return skin_; }
  std::size_t candidates() const { return kept_.candidates(); }
  double recentMotion() const;
  const SkinCosts& costs() const { return costs_; }

  /// Gives back the candidate list's memory (after a burst of large frames).
  void releaseMemory() { kept_ = SkinList(); }

 private:
  void learnPassCosts(double inMilliseconds, double inBoxes);
  void keepNoCandidates(const BoxColumns& inSwept, FrameReport& ioReport, PairList& ioPairs);

  SkinList kept_;      // kept candidates of the last grown sweep
  double skin_ = 0.0;  // the skin they were swept with
  // The smallest skin whose grown sweep went over the candidate budget, and at how many
  // boxes: until the count changes, a skin at least as large grows nothing (skin 0).
  double over_budget_skin_ = std::numeric_limits<double>::infinity();
  std::size_t over_budget_boxes_ = 0;
  bool over_budget_frame_ = false;  // this frame's skin went over the budget
  SkinCosts costs_;                 // what earlier frames measured
  double recent_motion_[tuning::kMotionWindow] = {};
  int motion_slot_ = 0;
  // This frame's kept-candidate work, for learn(): growing the boxes, keeping the grown
  // sweep's candidates, and the pass that answered the frame (gather and test).
  struct WorkTimes {
    double ms_grow = 0.0;
    double ms_keep = 0.0;
    double ms_pass = 0.0;
  } times_;
};

}  // namespace sap_broadphase
