#include "core/frame_history.h"
#include "core/assert.h"
#include "core/buffers.h"
#include "core/work_units.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace sap_broadphase {
namespace {

template <typename T>
void copySlice(const std::vector<T>& inFrom, std::vector<T>& outTo, std::size_t inBegin,
               std::size_t inEnd) {
  if (inFrom.empty()) return;  // groups and masks may be absent
  std::copy(inFrom.begin() + inBegin, inFrom.begin() + inEnd, outTo.begin() + inBegin);
}

// Copies elements [inBegin, inEnd) when some differ; true when they did.
bool copyIfDifferent(const std::vector<uint32_t>& inFrom, std::vector<uint32_t>& outTo,
                     std::size_t inBegin, std::size_t inEnd) {
  if (std::equal(inFrom.begin() + inBegin, inFrom.begin() + inEnd, outTo.begin() + inBegin))
    return false;
  copySlice(inFrom, outTo, inBegin, inEnd);
  return true;
}

uint64_t bitsOf(double inValue) {
  uint64_t bits;
  std::memcpy(&bits, &inValue, sizeof bits);
  return bits;
}

struct BlockChanges {
  std::size_t changed_boxes = 0;
  double max_displacement = 0.0;
};

// What one work unit of a comparison found (counts of blocks or boxes, as named).
struct UnitChanges {
  std::size_t moved = 0;            // boxes
  std::size_t filters_changed = 0;  // boxes
  std::size_t other_ids = 0;        // blocks with some other id
  std::size_t unusable = 0;         // record blocks with a box refused
  double max_displacement = 0.0;
};

void addChanges(UnitChanges& ioTotal, const UnitChanges& inUnit) {
  ioTotal.moved += inUnit.moved;
  ioTotal.filters_changed += inUnit.filters_changed;
  ioTotal.other_ids += inUnit.other_ids;
  ioTotal.unusable += inUnit.unusable;
  ioTotal.max_displacement = std::max(ioTotal.max_displacement, inUnit.max_displacement);
}

constexpr std::size_t kBlock = 512;  // boxes compared, then copied, together

// One bound array over a block of inCount boxes: ORs each box's differing bits into
// ioDiffering[k] and returns the bits of the largest change, 0 when bit for bit equal,
// infinite when the bound left or reached an infinity (no finite skin covers that). Changes
// are never negative nor NaN, so their bits order as the changes do: the maximum is an integer
// one, and the loop has no branch.
uint64_t compareBoundArray(const double* inNow, const double* inBefore, std::size_t inCount,
                           uint64_t* ioDiffering) {
  const uint64_t infinity_bits = bitsOf(HUGE_VAL);
  uint64_t largest = 0;
  for (std::size_t k = 0; k < inCount; ++k) {
    const uint64_t differs = bitsOf(inNow[k]) ^ bitsOf(inBefore[k]);
    const double change = std::fabs(inNow[k] - inBefore[k]);
    const uint64_t change_bits = differs == 0       ? 0
                                 : change != change ? infinity_bits
                                                    : bitsOf(change);
    ioDiffering[k] |= differs;
    largest = change_bits > largest ? change_bits : largest;
  }
  return largest;
}

// The six bound arrays of a frame from some box on: min x, y, z, then max x, y, z.
struct BoundArrays {
  const double* at[6];
};

BoundArrays boundArrays(const BoxSet& inBoxes, std::size_t inBegin) {
  BoundArrays arrays;
  for (int axis = 0; axis < 3; ++axis) {
    arrays.at[axis] = inBoxes.lo[axis].data() + inBegin;
    arrays.at[3 + axis] = inBoxes.hi[axis].data() + inBegin;
  }
  return arrays;
}

// inCount boxes, at most kBlock: outUnchanged[k] = 1 when every bound is bit for bit the one
// before (0.0 to -0.0 is a change of size 0), and the largest change of one bound.
BlockChanges compareBounds(const BoundArrays& inNow, const BoundArrays& inBefore,
                           std::size_t inCount, uint8_t* outUnchanged) {
  uint64_t differing[kBlock] = {};
  uint64_t largest = 0;
  for (int array = 0; array < 6; ++array)
    largest = std::max(largest,
                       compareBoundArray(inNow.at[array], inBefore.at[array], inCount, differing));
  BlockChanges changes;
  for (std::size_t k = 0; k < inCount; ++k) {
    outUnchanged[k] = differing[k] == 0;
    changes.changed_boxes += differing[k] != 0;
  }
  std::memcpy(&changes.max_displacement, &largest, sizeof largest);
  return changes;
}

// Clears outUnchanged[i] of boxes whose group or mask changed; returns how many did.
std::size_t markFilterChanges(const BoxSet& inNow, const BoxSet& inBefore, std::size_t inBegin,
                              std::size_t inEnd, uint8_t* ioUnchanged) {
  if (inNow.groups.empty() && inNow.masks.empty()) return 0;
  std::size_t changed = 0;
  for (std::size_t i = inBegin; i < inEnd; ++i) {
    const bool same_filter =
        inNow.group(i) == inBefore.group(i) && inNow.mask(i) == inBefore.mask(i);
    ioUnchanged[i] &= same_filter;
    changed += !same_filter;
  }
  return changed;
}

std::size_t countChanged(const uint8_t* inUnchanged, std::size_t inBegin, std::size_t inEnd) {
  std::size_t changed = 0;
  for (std::size_t i = inBegin; i < inEnd; ++i) changed += inUnchanged[i] == 0;
  return changed;
}

// A block of boxes read from records (InterleavedBoxes) into the layout the comparison and the
// copy read: each thread's, on its stack (28 KB, cache-resident while the block is handled).
struct RecordBlock {
  double bounds[6][kBlock];  // min x, y, z, then max x, y, z, as in a record
  uint32_t ids[kBlock];
};

BoundArrays boundArrays(const RecordBlock& inBlock) {
  BoundArrays arrays;
  for (int array = 0; array < 6; ++array) arrays.at[array] = inBlock.bounds[array];
  return arrays;
}

// Reads boxes [inBegin, inEnd) into outBlock and checks them on the way: false when some box
// has a NaN bound or min > max (`low <= high` is false exactly then, as in validate()).
bool readRecords(const InterleavedBoxes& inBoxes, std::size_t inBegin, std::size_t inEnd,
                 RecordBlock& outBlock) {
  bool usable = true;
  for (std::size_t i = inBegin; i < inEnd; ++i) {
    const double* record = inBoxes.bounds + 6 * i;
    for (int array = 0; array < 6; ++array) outBlock.bounds[array][i - inBegin] = record[array];
    for (int axis = 0; axis < 3; ++axis) usable &= record[axis] <= record[3 + axis];
  }
  for (std::size_t i = inBegin; i < inEnd; ++i)
    outBlock.ids[i - inBegin] = inBoxes.ids ? inBoxes.ids[i] : static_cast<uint32_t>(i);
  return usable;
}

}  // namespace

const FrameDelta& FrameHistory::load(const InterleavedBoxes& inBoxes, int inThreads,
                                     std::optional<ValidationError>& outProblem) {
  SAP_ASSERT(!inBoxes.hasFilters(), "load() takes frames without groups or masks");
  const bool had_last = valid_;
  delta_ = FrameDelta();
  threads_ = inThreads;
  valid_ = false;
  copied_ = true;  // last_ becomes the frame here: remember() has nothing to copy
  const bool comparable =
      had_last && last_.size() == inBoxes.count && last_.groups.empty() && last_.masks.empty();
  if (!comparable) {
    // A first frame, or other ids: every box copied, then checked as any BoxSet is.
    copyInterleaved(inBoxes, last_, inThreads);
    outProblem = validate(last_);
    if (had_last) delta_.relation = FrameRelation::kOtherIds;
  } else {
    const RecordsLoaded loaded = compareAndLoadBoxByBox(inBoxes, inThreads);
    // Same ids as a frame that passed: no id can repeat, and only a box found unusable on the
    // way needs the full check (which names the lowest bad box with validate()'s words).
    outProblem = loaded.other_ids || loaded.unusable ? validate(last_) : std::nullopt;
    if (loaded.other_ids) {
      delta_ = FrameDelta();
      delta_.relation = FrameRelation::kOtherIds;
    } else {
      delta_.relation =
          delta_.moved_boxes == 0 ? FrameRelation::kIdentical : FrameRelation::kSameIds;
      delta_.unchanged = &unchanged_;
    }
  }
  if (outProblem) forget();
  return delta_;
}

// compareAndCopyBoxByBox() for records: each block is read into a cache-resident scratch
// (checked on the way), compared with the copy and written into it where some box differs,
// so the caller's memory is read once and no other copy of the frame is made.
FrameHistory::RecordsLoaded FrameHistory::compareAndLoadBoxByBox(const InterleavedBoxes& inBoxes,
                                                                 int inThreads) {
  const std::size_t n = inBoxes.count;
  unchanged_.resize(n);
  const UnitChanges changes = reduceOverItems(
      WorkUnits{n}, inThreads, UnitChanges{},
      [&](std::size_t inBegin, std::size_t inEnd) {
        UnitChanges unit;
        RecordBlock block;
        for (std::size_t begin = inBegin; begin < inEnd; begin += kBlock) {
          const std::size_t end = std::min(inEnd, begin + kBlock), count = end - begin;
          unit.unusable += !readRecords(inBoxes, begin, end, block);
          if (!std::equal(block.ids, block.ids + count, last_.ids.begin() + begin)) {
            std::copy(block.ids, block.ids + count, last_.ids.begin() + begin);
            ++unit.other_ids;
          }
          const BlockChanges bounds = compareBounds(boundArrays(block), boundArrays(last_, begin),
                                                    count, unchanged_.data() + begin);
          if (bounds.changed_boxes > 0) {
            for (int axis = 0; axis < 3; ++axis) {
              std::copy(block.bounds[axis], block.bounds[axis] + count,
                        last_.lo[axis].begin() + begin);
              std::copy(block.bounds[3 + axis], block.bounds[3 + axis] + count,
                        last_.hi[axis].begin() + begin);
            }
            unit.moved += bounds.changed_boxes;
          }
          unit.max_displacement = std::max(unit.max_displacement, bounds.max_displacement);
        }
        return unit;
      },
      addChanges);
  delta_.moved_boxes = changes.moved;
  delta_.max_displacement = changes.max_displacement;
  return RecordsLoaded{changes.other_ids != 0, changes.unusable != 0};
}

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

// One pass over the boxes in work units (work_units.h), block by block: a block is compared with
// its copy without a branch and, where some box of it differs, copied at once while both are
// in the cache (a separate copy after the sweep would read both frames from memory again;
// copying a whole block keeps the copy a plain streaming one, and unchanged boxes in it are
// rewritten with their own bits). Returns false when some id differs; the ids are copied too,
// so that last_ equals inBoxes in every case.
bool FrameHistory::compareAndCopyBoxByBox(const BoxSet& inBoxes, int inThreads) {
  const std::size_t n = inBoxes.size();
  unchanged_.resize(n);
  const UnitChanges changes = reduceOverItems(
      WorkUnits{n}, inThreads, UnitChanges{},
      [&](std::size_t inBegin, std::size_t inEnd) {
        UnitChanges unit;
        for (std::size_t begin = inBegin; begin < inEnd; begin += kBlock) {
          const std::size_t end = std::min(inEnd, begin + kBlock);
          if (copyIfDifferent(inBoxes.ids, last_.ids, begin, end)) ++unit.other_ids;
          const BlockChanges bounds =
              compareBounds(boundArrays(inBoxes, begin), boundArrays(last_, begin), end - begin,
                            unchanged_.data() + begin);
          const std::size_t filters =
              markFilterChanges(inBoxes, last_, begin, end, unchanged_.data());
          if (bounds.changed_boxes > 0 || filters > 0) {
            for (int axis = 0; axis < 3; ++axis) {
              copySlice(inBoxes.lo[axis], last_.lo[axis], begin, end);
              copySlice(inBoxes.hi[axis], last_.hi[axis], begin, end);
            }
            copySlice(inBoxes.groups, last_.groups, begin, end);
            copySlice(inBoxes.masks, last_.masks, begin, end);
            unit.moved += countChanged(unchanged_.data(), begin, end);
          }
          unit.filters_changed += filters;
          unit.max_displacement = std::max(unit.max_displacement, bounds.max_displacement);
        }
        return unit;
      },
      addChanges);
  delta_.moved_boxes = changes.moved;
  delta_.filters_changed = changes.filters_changed != 0;
  delta_.max_displacement = changes.max_displacement;
  return changes.other_ids == 0;
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
  if (!copied_) copyWholeFrame(inBoxes, threads_);
  valid_ = true;
  copied_ = false;
  // Only the boxes compare() found changed were copied: the copy must now be the frame.
  SAP_ASSERT(sameBoxes(last_, inBoxes), "the frame history's copy differs from the frame");
}

// A first frame, or other ids: every box copied, unit by unit (vectors keep their
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
  runOverItems(WorkUnits{n}, inThreads, [&](std::size_t inBegin, std::size_t inEnd) {
    copySlice(inBoxes.ids, last_.ids, inBegin, inEnd);
    for (int axis = 0; axis < 3; ++axis) {
      copySlice(inBoxes.lo[axis], last_.lo[axis], inBegin, inEnd);
      copySlice(inBoxes.hi[axis], last_.hi[axis], inBegin, inEnd);
    }
    copySlice(inBoxes.groups, last_.groups, inBegin, inEnd);
    copySlice(inBoxes.masks, last_.masks, inBegin, inEnd);
  });
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
