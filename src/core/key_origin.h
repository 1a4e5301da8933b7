// Where the sort keys of an axis are measured from: shared by the sweep (sweep_and_prune.h)
// and the small-frame path (small_frame.h), whose float tests must round exactly as the
// sweep's keys do.
#pragma once

#include <cstdint>

#include "sap_broadphase/core/box_set.h"

namespace sap_broadphase {

/// Where the sort keys of one axis are measured from. Keys are float32 images of
/// (coordinate - origin), rounded outward exactly (the float64 difference is rounded to
/// nearest, and its rounding error, recovered exactly by TwoSum, decides whether the key must
/// step one further out). Near the origin float32 resolves far finer than at 4e6 m (UTM,
/// ECEF), where boxes of a few centimetres would all share keys and become mutual candidates.
///
/// low() and high() are defined in sweep_and_prune.cpp, next to the branch-free key functions
/// (lowKeyFlat, highKeyFlat) that the sweep's gather inlines as well.
struct KeyOrigin {
  double origin[3] = {0.0, 0.0, 0.0};
  uint32_t low(int inAxis, double inValue) const;
  uint32_t high(int inAxis, double inValue) const;
};

/// The key origin a sweep of inBoxes starts from: per axis 0, or the centre of the finite
/// bounds when the frame lies far from 0 (tuning::kFarFromOriginInSpans). Later frames keep
/// an origin while the frame stays near it.
KeyOrigin keyOriginOf(const BoxSet& inBoxes, int inThreads);

}  // namespace sap_broadphase
