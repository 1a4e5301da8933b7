#include "core/frame_history.h"
#include "core/assert.h"
#include "core/buffers.h"
#include "core/tuning.h"
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

constexpr std::size_t kBlock = tuning::kHistoryBlockBoxes;
static_assert(kUnitBoxes % kBlock == 0, "a work unit is whole blocks");

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

// One block of the frame as the comparison reads it: its six bound arrays and its ids (in the
// frame itself for a BoxSet, in the thread's scratch for records), and whether every bound of
// it is usable.
struct BlockView {
  BoundArrays bounds;
  const uint32_t* ids;
  bool usable;
};

// A frame given as a BoxSet: its blocks are views of its arrays; groups and masks are compared
// and copied with the bounds.
struct BoxSetFrame {
  const BoxSet& boxes;
  struct Scratch {};
  std::size_t size() const { return boxes.size(); }
  BlockView block(std::size_t inBegin, std::size_t /*inEnd*/, Scratch& /*ioScratch*/) const {
    return {boundArrays(boxes, inBegin), boxes.ids.data() + inBegin, true};
  }
  std::size_t markFilterChanges(const BoxSet& inLast, std::size_t inBegin, std::size_t inEnd,
                                uint8_t* ioUnchanged) const {
    return sap_broadphase::markFilterChanges(boxes, inLast, inBegin, inEnd, ioUnchanged);
  }
  void copyFilters(BoxSet& ioLast, std::size_t inBegin, std::size_t inEnd) const {
    copySlice(boxes.groups, ioLast.groups, inBegin, inEnd);
    copySlice(boxes.masks, ioLast.masks, inBegin, inEnd);
  }
};

// A frame given as records, without groups or masks: each block is read into the thread's
// scratch (checked on the way), so the caller's memory is read once.
struct RecordFrame {
  const InterleavedBoxes& boxes;
  using Scratch = RecordBlock;
  std::size_t size() const { return boxes.count; }
  BlockView block(std::size_t inBegin, std::size_t inEnd, RecordBlock& ioScratch) const {
    const bool usable = readRecords(boxes, inBegin, inEnd, ioScratch);
    return {boundArrays(ioScratch), ioScratch.ids, usable};
  }
  std::size_t markFilterChanges(const BoxSet&, std::size_t, std::size_t, uint8_t*) const {
    return 0;
  }
  void copyFilters(BoxSet&, std::size_t, std::size_t) const {}
};

// One pass over the boxes in work units (work_units.h), block by block: a block is compared with
// ioLast's without a branch and, where some box of it differs, copied at once while both are
// in the cache (a separate copy after the sweep would read both frames from memory again;
// copying a whole block keeps the copy a plain streaming one, and unchanged boxes in it are
// rewritten with their own bits). The ids are copied too, so that ioLast equals the frame in
// every case. ioLast has the frame's size, and groups and masks where the frame has them.
template <typename Frame>
FramePass compareAndCopyBlocks(const Frame& inFrame, int inThreads, BoxSet& ioLast,
                               std::vector<uint8_t>& outUnchanged) {
  const std::size_t n = inFrame.size();
  outUnchanged.resize(n);
  const UnitChanges changes = reduceOverItems(
      WorkUnits{n}, inThreads, UnitChanges{},
      [&](std::size_t inBegin, std::size_t inEnd) {
        UnitChanges unit;
        typename Frame::Scratch scratch;
        for (std::size_t begin = inBegin; begin < inEnd; begin += kBlock) {
          const std::size_t end = std::min(inEnd, begin + kBlock), count = end - begin;
          const BlockView block = inFrame.block(begin, end, scratch);
          unit.unusable += !block.usable;
          if (!std::equal(block.ids, block.ids + count, ioLast.ids.begin() + begin)) {
            std::copy(block.ids, block.ids + count, ioLast.ids.begin() + begin);
            ++unit.other_ids;
          }
          const BlockChanges bounds = compareBounds(block.bounds, boundArrays(ioLast, begin), count,
                                                    outUnchanged.data() + begin);
          const std::size_t filters =
              inFrame.markFilterChanges(ioLast, begin, end, outUnchanged.data());
          if (bounds.changed_boxes > 0 || filters > 0) {
            for (int axis = 0; axis < 3; ++axis) {
              std::copy(block.bounds.at[axis], block.bounds.at[axis] + count,
                        ioLast.lo[axis].begin() + begin);
              std::copy(block.bounds.at[3 + axis], block.bounds.at[3 + axis] + count,
                        ioLast.hi[axis].begin() + begin);
            }
            inFrame.copyFilters(ioLast, begin, end);
            unit.moved += countChanged(outUnchanged.data(), begin, end);
          }
          unit.filters_changed += filters;
          unit.max_displacement = std::max(unit.max_displacement, bounds.max_displacement);
        }
        return unit;
      },
      addChanges);
  SAP_ASSERT(changes.moved == countChanged(outUnchanged.data(), 0, n), "moved boxes miscounted");
  SAP_ASSERT(!(changes.max_displacement < 0.0), "a negative or NaN displacement");
  return {changes.moved, changes.other_ids != 0, changes.unusable != 0,
          changes.filters_changed != 0, changes.max_displacement};
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
    const FramePass pass = compareAndCopyBlocks(RecordFrame{inBoxes}, inThreads, last_, unchanged_);
    // Same ids as a frame that passed: no id can repeat, and only a box found unusable on the
    // way needs the full check (which names the lowest bad box with validate()'s words).
    outProblem = pass.other_ids || pass.unusable ? validate(last_) : std::nullopt;
    describeSameSize(pass);
  }
  if (outProblem) forget();
  SAP_ASSERT(outProblem || last_.size() == inBoxes.count, "the loaded frame lost boxes");
  SAP_ASSERT(delta_.moved_boxes <= inBoxes.count, "more boxes moved than the frame holds");
  return delta_;
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
  describeSameSize(compareAndCopyBlocks(BoxSetFrame{inBoxes}, inThreads, last_, unchanged_));
  SAP_ASSERT(unchanged_.size() == inBoxes.size(), "one unchanged flag per box");
  return delta_;
}

void FrameHistory::describeSameSize(const FramePass& inPass) {
  delta_ = FrameDelta();
  delta_.relation = FrameRelation::kOtherIds;
  if (inPass.other_ids) return;
  delta_.relation = inPass.moved_boxes == 0 ? FrameRelation::kIdentical : FrameRelation::kSameIds;
  delta_.moved_boxes = inPass.moved_boxes;
  delta_.filters_changed = inPass.filters_changed;
  delta_.max_displacement = inPass.max_displacement;
  delta_.unchanged = &unchanged_;
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
