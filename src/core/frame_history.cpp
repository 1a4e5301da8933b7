#include "core/frame_history.h"
#include "core/assert.h"
#include "core/buffers.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace sap_broadphase {
namespace {

bool sameBits(double inA, double inB) {
  return std::memcmp(&inA, &inB, sizeof inA) == 0;
}

// How far one bound moved: 0 when bit for bit equal, infinite when it left or reached an
// infinity (no finite skin covers that).
double boundChange(double inNow, double inBefore) {
  if (sameBits(inNow, inBefore)) return 0.0;
  const double change = std::fabs(inNow - inBefore);
  return std::isnan(change) ? HUGE_VAL : change;
}

}  // namespace

const FrameDelta& FrameHistory::compare(const BoxSet& inBoxes, int inThreads) {
  delta_ = FrameDelta();
  if (!valid_) return delta_;
  delta_.relation = FrameRelation::kOtherIds;
  if (!sameElements(last_.ids, inBoxes.ids) || last_.groups.empty() != inBoxes.groups.empty() ||
      last_.masks.empty() != inBoxes.masks.empty())
    return delta_;
  compareBoxByBox(inBoxes, inThreads);
  delta_.relation = delta_.moved_boxes == 0 ? FrameRelation::kIdentical : FrameRelation::kSameIds;
  delta_.unchanged = &unchanged_;
  return delta_;
}

void FrameHistory::compareBoxByBox(const BoxSet& inBoxes, int inThreads) {
  const std::size_t n = inBoxes.size();
  unchanged_.resize(n);
  std::size_t moved = 0, filters_changed = 0;
  double max_displacement = 0.0;
#pragma omp parallel for num_threads(inThreads) schedule(static) \
    reduction(+ : moved, filters_changed) reduction(max : max_displacement)
  for (std::size_t i = 0; i < n; ++i) {
    const bool same_filter = inBoxes.group(i) == last_.group(i) && inBoxes.mask(i) == last_.mask(i);
    double displacement = 0.0;
    for (int axis = 0; axis < 3; ++axis)
      displacement = std::max({displacement, boundChange(inBoxes.lo[axis][i], last_.lo[axis][i]),
                               boundChange(inBoxes.hi[axis][i], last_.hi[axis][i])});
    // A bound that changed by less than the smallest double (0.0 to -0.0) still changed.
    bool same_bounds = displacement == 0.0;
    for (int axis = 0; axis < 3 && same_bounds; ++axis)
      same_bounds = sameBits(inBoxes.lo[axis][i], last_.lo[axis][i]) &&
                    sameBits(inBoxes.hi[axis][i], last_.hi[axis][i]);
    const bool unchanged = same_filter && same_bounds;
    unchanged_[i] = unchanged;
    moved += !unchanged;
    filters_changed += !same_filter;
    max_displacement = std::max(max_displacement, displacement);
  }
  delta_.moved_boxes = moved;
  delta_.filters_changed = filters_changed != 0;
  delta_.max_displacement = max_displacement;
}

namespace {

// Bit for bit the same boxes (ids, bounds, groups, masks).
bool sameBoxes(const BoxSet& inA, const BoxSet& inB) {
  bool same = sameElements(inA.ids, inB.ids) && sameElements(inA.groups, inB.groups) &&
              sameElements(inA.masks, inB.masks);
  for (int axis = 0; axis < 3; ++axis)
    same = same && sameElements(inA.lo[axis], inB.lo[axis]) &&
           sameElements(inA.hi[axis], inB.hi[axis]);
  return same;
}

}  // namespace

void FrameHistory::remember(const BoxSet& inBoxes) {
  rememberChanges(inBoxes);
  // Only the boxes compare() found changed were copied: the copy must now be the frame.
  SAP_ASSERT(sameBoxes(last_, inBoxes), "the frame history's copy differs from the frame");
}

void FrameHistory::rememberChanges(const BoxSet& inBoxes) {
  if (!valid_ || delta_.relation == FrameRelation::kFirst ||
      delta_.relation == FrameRelation::kOtherIds || unchanged_.size() != inBoxes.size()) {
    last_ = inBoxes;  // vectors keep their capacity
    valid_ = true;
    return;
  }
  if (delta_.relation == FrameRelation::kIdentical) return;
  for (std::size_t i = 0; i < inBoxes.size(); ++i) {
    if (unchanged_[i]) continue;
    for (int axis = 0; axis < 3; ++axis) {
      last_.lo[axis][i] = inBoxes.lo[axis][i];
      last_.hi[axis][i] = inBoxes.hi[axis][i];
    }
    if (!inBoxes.groups.empty()) last_.groups[i] = inBoxes.groups[i];
    if (!inBoxes.masks.empty()) last_.masks[i] = inBoxes.masks[i];
  }
}

void FrameHistory::forget() {
  valid_ = false;
  delta_ = FrameDelta();
}

void FrameHistory::shrinkToFit() {
  last_ = BoxSet(last_);  // a copy holds only what is used
  unchanged_.shrink_to_fit();
}

}  // namespace sap_broadphase
