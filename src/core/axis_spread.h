// How boxes spread along one axis: the finite span of their bounds and their mean finite
// extent. The slab grid, the static index's grid, the key origins and the skin's cost model
// all size themselves from it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "sap_broadphase/core/box_set.h"

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

/// The spread of the boxes of inBoxes on axis inAxis, of those at inIndexes only when given.
AxisSpread measureAxisSpread(const BoxSet& inBoxes, int inAxis, int inThreads,
                             const std::vector<uint32_t>* inIndexes = nullptr);

}  // namespace sap_broadphase
