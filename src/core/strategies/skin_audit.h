// Whether the automatic skin pays, as measured rather than as predicted.
//
// The skin's cost model (frame_plan.cpp) predicts a cycle of kept-candidate frames from costs
// learnt a part at a time, and misses what it does not model: the successor's build a step a
// frame, the coverage test, a wider skin's candidates leaving the caches. Measured on the 2-core
// VM (uniform, 2^17, d = 0.05, boxes moving 0.05 edges a frame, 2 threads, 100 frames), the
// model chose skins whose kept-candidate frames cost 8-12 ms against 4.2 ms for a plain frame:
// a mean frame of 15.3 ms against 4.7 ms with the skin off; with the audit, 8.3 ms (the skin
// retried after each probation).
//
// The audit weighs what the frames cost: the mean, a box, of the frames a skin answered (grown
// sweeps, kept-candidate passes and the successor's steps together, over kSkinAuditFrames; not
// the grown sweep that starts a skin after plain frames, paid once for all the frames it answers)
// against the plain frames' cost a box. When the skin's frames cost more, the skin is off for a
// probation of plain frames, which refreshes the plain cost, doubled each time the skin fails
// again; then the model may choose a skin again.
#pragma once

#include <cstddef>

#include "core/frame/frame_history.h"
#include "core/frame/frame_plan.h"
#include "core/tuning.h"

namespace sap_broadphase {

class SkinAudit {
 public:
  /// A frame's work that ran inPlan for inDelta on inBoxes boxes, in inMilliseconds (the plan
  /// and its strategy: what differs between a skin's frame and a plain one).
  void record(const FramePlan& inPlan, const FrameDelta& inDelta, std::size_t inBoxes,
              double inMilliseconds);

  /// False until a plain frame of these ids has been measured (nothing to weigh a skin
  /// against), and through a probation.
  bool allowsSkin() const { return plain_ns_per_box_ > 0.0 && probation_left_ == 0; }

  /// For tests: plain frames left in the current probation, and the next probation's length.
  int probationLeft() const { return probation_left_; }
  int nextProbation() const { return next_probation_; }

 private:
  void judgeSkin();

  double plain_ns_per_box_ = 0.0;  // smoothed; 0: no plain frame measured yet
  double skin_ns_per_box_sum_ = 0.0;
  int skin_frames_ = 0;     // in the window being gathered
  bool skin_live_ = false;  // the last plain or skin frame was a skin's
  int probation_left_ = 0;
  int next_probation_ = tuning::kSkinAuditFirstProbation;
};

}  // namespace sap_broadphase
