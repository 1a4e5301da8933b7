// Skin reuse as the engine uses it: the kept candidates (skin_list.h), the skin they were
// swept with, the recent motion of the boxes and the learnt costs of plain and grown sweeps
// and of kept-candidate passes, which the plan (frame_plan.h) weighs to choose a skin.
//
// Before a frame is planned, coversFrame() answers whether the boxes about to be swept still
// lie inside the skin of the kept candidates (and gathers their bounds on the way), so that the
// plan is right the first time: a kept-candidate frame is then only the candidates' test.
//
// The next kept candidates are built before the current ones run out, a piece a frame
// (advanceSuccessor): a snapshot of the boxes grown by the skin, then one slab of it along
// its sort axis swept a frame, then their adoption. When the current candidates no longer
// cover a frame, the successor's are tried; a steady frame thus pays a slab of a grown sweep
// rather than a whole one every cycle.
#pragma once

#include <cstddef>
#include <limits>

#include "core/frame/box_columns.h"
#include "core/frame/frame_history.h"
#include "core/frame/frame_plan.h"
#include "core/frame/pair_sort.h"
#include "core/strategies/skin_list.h"
#include "core/strategies/small_frame.h"
#include "core/sweep/axis_spread.h"
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
  /// gathered for answerFromCandidates(). When the kept candidates do not cover the frame but
  /// a successor is ready and does, the successor becomes the kept candidates.
  bool coversFrame(const BoxColumns& inSwept, FrameReport& ioReport);
  /// FramePath::kSkin, after coversFrame() said yes: the candidates that overlap
  /// now, in canonical order, into outPairs (replaced).
  void answerFromCandidates(FrameReport& ioReport, PairList& outPairs);

  /// After answerFromCandidates(): one step of building the next kept candidates from the
  /// boxes of this frame, inSwept, once the current ones are expected to run out within the
  /// steps that building takes (a snapshot, then a slab of its sweep a frame, then adoption).
  void advanceSuccessor(const BoxColumns& inSwept, FrameReport& ioReport);

  /// A grown sweep, first half: inSwept grown by inSkin / 2 a side, for the sweep to run on
  /// (valid until the next grow()).
  const BoxColumns& grow(const BoxColumns& inSwept, double inSkin, FrameReport& ioReport);
  /// A grown sweep, second half: ioPairs holds the grown boxes' pairs; they become the kept
  /// candidates, and ioPairs the pairs of inSwept among them.
  void keepAndAnswer(const BoxColumns& inSwept, FrameReport& ioReport, PairList& ioPairs);
  /// Forgets the kept candidates (a plain sweep, a small frame or reset()).
  void forget() {
    kept_.clear();
    abandonSuccessor();
  }

  /// Learns from a frame that ran inPlan on the boxes of ioSwept (their spread, measured here
  /// if the frame has not yet): a sweep's costs per box and per item (from the sweep phases of
  /// inReport, with inSweepPairs its pairs or kept candidates) and the costs of growing,
  /// keeping and passing.
  void learn(const FramePlan& inPlan, FrameSpread& ioSwept, std::size_t inSweepPairs,
             const FrameReport& inReport);

  /// True when this frame's skin went over the kept-candidate budget (keptCandidateBudget):
  /// the frame kept no candidates, or swept its boxes ungrown; its report says kOverBudget.
  bool overBudget() const { return over_budget_frame_; }

  /// True while a successor is built or ready (for tests).
  bool buildingSuccessor() const { return next_.steps > 0; }
  /// The kept candidates (for tests).
  const SkinList& keptCandidates() const { return kept_; }
  /// Times a ready successor took over from the kept candidates (for tests).
  std::size_t successorsTaken() const { return successors_taken_; }

  /// Bytes the successor holds (capacities), by part: for the memory experiment
  /// (bench/exp_memory.cpp) and tests. Its slab sweep's buffers (order, slab, kernel, slab ids) are
  /// held from its snapshot to its last slab only, the rest until it takes over or is given up.
  struct SuccessorMemoryUse {
    SkinList::MemoryUse list;  ///< its grown boxes, then its candidates (SkinList's parts)
    std::size_t found = 0;     ///< the candidates its slabs found so far
    std::size_t order = 0;     ///< box order and grown high ends along its sort axis
    std::size_t slab = 0;      ///< one slab's boxes, positions and pairs
    std::size_t kernel = 0;    ///< the small-frame kernel's workspace that sweeps a slab
    std::size_t slab_ids = 0;  ///< the slab's boxes by real id (the kernel's ids are their ranks)
    std::size_t total() const {
      return list.reference + list.candidates + list.pass + list.scratch + found + order + slab +
             kernel + slab_ids;
    }
  };
  SuccessorMemoryUse successorMemoryUse() const;
  /// Bytes the kept candidates hold, by part (SkinList::memoryUse).
  SkinList::MemoryUse keptMemoryUse() const { return kept_.memoryUse(); }

  /// What the plan weighs.
  bool hasCandidates() const { return kept_.valid(); }
  double skin() const { return skin_; }
  std::size_t candidates() const { return kept_.candidates(); }
  double recentMotion() const;
  const SkinCosts& costs() const { return costs_; }

  /// Gives back the candidate list's memory (after a burst of large frames).
  void releaseMemory() {
    kept_ = SkinList();
    next_ = Successor();
  }

 private:
  void learnPassCosts(double inMilliseconds, double inBoxes);
  void keepNoCandidates(const BoxColumns& inSwept, FrameReport& ioReport, PairList& ioPairs);
  void abandonSuccessor();
  void recycleSuccessor();
  void releaseSlabWork();
  void mergeSlabPairs(const PairList& inSlabPairs);
  void snapshotSuccessor(const BoxColumns& inSwept, double inSkin, int inSlabs);
  void sweepSuccessorSlab();
  void adoptSuccessor();

  SkinList kept_;      // kept candidates of the last grown sweep
  double skin_ = 0.0;  // the skin they were swept with
  // The skin of the last grown sweep, as the plan chose it: a successor is grown by it plus
  // the motion of the frames it takes to build.
  double planned_skin_ = 0.0;
  int kept_age_ = 0;  // frames since the boxes they were grown from
  // The next kept candidates, built a step a frame: step 1 grows a snapshot of the frame's
  // boxes and sorts it by grown low end on one axis; steps 2..slabs+1 sweep one slab of that
  // order each, keeping the pairs whose later box (in the order) lies in the slab; the last
  // step adopts them. Ready, they wait for the kept candidates to stop covering a frame.
  // The buffers of the slab sweep are given back before the adoption (releaseSlabWork), whose
  // candidate arrays are the build's memory peak; when it takes over, all but the replaced
  // candidates' grown boxes, whose columns the next snapshot reuses (recycleSuccessor).
  struct Successor {
    SkinList list;                 // the snapshot's grown boxes, then its candidates
    double skin = 0.0;             // the skin it was grown by
    int age = 0;                   // frames since its snapshot
    int slabs = 0;                 // slabs of its sweep
    int steps = 0;                 // steps taken; 0: none being built
    bool ready = false;            // adopted: it may take over
    int axis = 0;                  // the axis of its order
    Buffer<uint32_t> order;        // box indexes by grown low end on that axis
    Buffer<double> high_in_order;  // their grown high ends on it, in that order
    PairList found;                // candidates found so far, canonical (merged in place)
    PairList slab_pairs;           // one slab's

    Buffer<uint32_t> slab_members;  // positions of the slab's boxes
    BoxColumns slab_boxes;          // one slab's boxes and those before it that reach into it
    SmallFrameWorkspace kernel;
    Buffer<uint32_t> slab_by_id;  // the slab's boxes by real id (the kernel's ids: their ranks)
  } next_;
  std::size_t successors_taken_ = 0;
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
