// How boxes spread along one axis: the finite span of their bounds and their mean finite
// extent. The slab grid, the static index's grid, the key origins and the skin's cost model
// all size themselves from it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/frame/box_columns.h"

namespace sap_broadphase {

struct AxisSpread {
  double lowest = std::numeric_limits<double>::infinity();    ///< least finite low bound
  double highest = -std::numeric_limits<double>::infinity();  ///< greatest finite high bound
  double extent_sum = 0.0;       ///< sum of the finite extents (high - low)
  std::size_t finite_boxes = 0;  ///< boxes with a finite extent

  /// True when some low and some high bound are finite, the low one not above the high one.
  bool hasSpan() const { return lowest <= highest; }
  /// highest - lowest (0 without a span; may overflow to infinity).
  double span() const { return hasSpan() ? highest - lowest : 0.0; }
  /// Mean finite extent (0 without finite boxes).
  double meanExtent() const {
    return finite_boxes ? extent_sum / static_cast<double>(finite_boxes) : 0.0;
  }
};

/// The spread of the boxes of inBoxes on axis inAxis, of those at inIndexes only when given,
/// measured on the threads of the runner's scope (passThreads()).
AxisSpread measureAxisSpread(const BoxColumns& inBoxes, int inAxis,
                             const std::vector<uint32_t>* inIndexes = nullptr);

/// The spread of one box set on each axis, each axis measured once, when first asked for: a
/// frame's key origins, slab grid, small-frame axis and skin cost model all read the same
/// measurement instead of each walking the boxes again. Lives for one frame (the boxes it
/// points at must not change meanwhile).
class FrameSpread {
 public:
  explicit FrameSpread(const BoxColumns& inBoxes) : boxes_(&inBoxes) {}

  /// The spread on inAxis, measured on the scope's threads if not measured yet (the same
  /// spread for any thread count).
  const AxisSpread& axis(int inAxis) {
    if (!measured_[inAxis]) {
      spreads_[inAxis] = measureAxisSpread(*boxes_, inAxis);
      measured_[inAxis] = true;
    }
    return spreads_[inAxis];
  }
  /// The same for callers that still name a count: the count is not read (the spread is the
  /// same for any count, and the threads are the scope's). Goes once they no longer pass one.
  const AxisSpread& axis(int inAxis, int /*inUnusedThreads*/) { return axis(inAxis); }
  const BoxColumns& boxes() const { return *boxes_; }

 private:
  const BoxColumns* boxes_;
  AxisSpread spreads_[3];
  bool measured_[3] = {false, false, false};
};

}  // namespace sap_broadphase
