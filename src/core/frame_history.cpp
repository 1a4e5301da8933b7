#include "core/frame_history.h"
#include "core/assert.h"
#include "core/buffers.h"

#include <omp.h>

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
  threads_ = inThreads;
  copied_ = false;
  if (!valid_) return delta_;
  valid_ = false;  // from here until remember(), last_ is being made this frame
  delta_.relation = FrameRelation::kOtherIds;
  if (last_.size() != inBoxes.size() || last_.groups.empty() != inBoxes.groups.empty() ||
      last_.masks.empty() != inBoxes.masks.empty())
    return delta_;
  copied_ = true;
  if (!compareAndCopyBoxByBox(inBoxes, inThreads)) {
    delta_ = FrameDelta();
    delta_.relation = FrameRelation::kOtherIds;
    return delta_;
  }
  delta_.relation = delta_.moved_boxes == 0 ? FrameRelation::kIdentical : FrameRelation::kSameIds;
  delta_.unchanged = &unchanged_;
  return delta_;
}

// One pass, each thread over its slice of the boxes: a box is compared with its copy and,
// where it differs, copied at once, while both are in the cache (a separate copy after the
// sweep would read both frames from memory a second time). Returns false when some id
// differs; the ids are copied too, so that last_ equals inBoxes in every case.
bool FrameHistory::compareAndCopyBoxByBox(const BoxSet& inBoxes, int inThreads) {
  const std::size_t n = inBoxes.size();
  unchanged_.resize(n);
  const bool has_groups = !inBoxes.groups.empty(), has_masks = !inBoxes.masks.empty();
  std::size_t moved = 0, filters_changed = 0, other_ids = 0;
  double max_displacement = 0.0;
#pragma omp parallel for num_threads(inThreads) schedule(static) \
    reduction(+ : moved, filters_changed, other_ids) reduction(max : max_displacement)
  for (std::size_t i = 0; i < n; ++i) {
    if (inBoxes.ids[i] != last_.ids[i]) {
      ++other_ids;
      last_.ids[i] = inBoxes.ids[i];
    }
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
    if (!unchanged) {
      for (int axis = 0; axis < 3; ++axis) {
        last_.lo[axis][i] = inBoxes.lo[axis][i];
        last_.hi[axis][i] = inBoxes.hi[axis][i];
      }
      if (has_groups) last_.groups[i] = inBoxes.groups[i];
      if (has_masks) last_.masks[i] = inBoxes.masks[i];
    }
    moved += !unchanged;
    filters_changed += !same_filter;
    max_displacement = std::max(max_displacement, displacement);
  }
  delta_.moved_boxes = moved;
  delta_.filters_changed = filters_changed != 0;
  delta_.max_displacement = max_displacement;
  return other_ids == 0;
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

template <typename T>
void copySlice(const std::vector<T>& inFrom, std::vector<T>& outTo, std::size_t inBegin,
               std::size_t inEnd) {
  if (inFrom.empty()) return;  // groups and masks may be absent
  std::copy(inFrom.begin() + inBegin, inFrom.begin() + inEnd, outTo.begin() + inBegin);
}

}  // namespace

void FrameHistory::remember(const BoxSet& inBoxes) {
  if (!copied_) copyWholeFrame(inBoxes, threads_);
  valid_ = true;
  copied_ = false;
  // Only the boxes compare() found changed were copied: the copy must now be the frame.
  SAP_ASSERT(sameBoxes(last_, inBoxes), "the frame history's copy differs from the frame");
}

// A first frame, or other ids: every box copied, each thread its slice (vectors keep their
// capacity, so only a larger frame than any before allocates).
void FrameHistory::copyWholeFrame(const BoxSet& inBoxes, int inThreads) {
  const std::size_t n = inBoxes.size();
  last_.ids.resize(n);
  for (int axis = 0; axis < 3; ++axis) {
    last_.lo[axis].resize(n);
    last_.hi[axis].resize(n);
  }
  last_.groups.resize(inBoxes.groups.size());
  last_.masks.resize(inBoxes.masks.size());
#pragma omp parallel num_threads(inThreads)
  {
    const auto team = static_cast<std::size_t>(omp_get_num_threads());
    const auto thread = static_cast<std::size_t>(omp_get_thread_num());
    const std::size_t begin = n * thread / team, end = n * (thread + 1) / team;
    copySlice(inBoxes.ids, last_.ids, begin, end);
    for (int axis = 0; axis < 3; ++axis) {
      copySlice(inBoxes.lo[axis], last_.lo[axis], begin, end);
      copySlice(inBoxes.hi[axis], last_.hi[axis], begin, end);
    }
    copySlice(inBoxes.groups, last_.groups, begin, end);
    copySlice(inBoxes.masks, last_.masks, begin, end);
  }
}

void FrameHistory::forget() {
  valid_ = copied_ = false;
  delta_ = FrameDelta();
}

void FrameHistory::shrinkToFit() {
  last_ = BoxSet(last_);  // a copy holds only what is used
  unchanged_.shrink_to_fit();
}

}  // namespace sap_broadphase
