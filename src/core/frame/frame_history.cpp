#include "core/frame/frame_history.h"
#include "core/assert.h"
#include "core/frame/box_columns.h"
#include "core/runner/buffers.h"
#include "core/runner/work_units.h"
#include "core/tuning.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace sap_broadphase {
namespace {

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

BoundArrays boundArrays(const BoxColumns& inBoxes, std::size_t inBegin) {
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

std::size_t countChanged(const uint8_t* inUnchanged, std::size_t inBegin, std::size_t inEnd) {
  std::size_t changed = 0;
  for (std::size_t i = inBegin; i < inEnd; ++i) changed += inUnchanged[i] == 0;
  return changed;
}

// A block of the frame's records read into the layout the comparison and the copy read: each
// thread's, on its stack (about 32 KB, cache-resident while the block is handled).
struct RecordBlock {
  double bounds[6][kBlock];  // min x, y, z, then max x, y, z, as in a record
  uint32_t ids[kBlock];
  uint32_t groups[kBlock];  // filtered frames only
  uint32_t masks[kBlock];
};

BoundArrays boundArrays(const RecordBlock& inBlock) {
  BoundArrays arrays;
  for (int array = 0; array < 6; ++array) arrays.at[array] = inBlock.bounds[array];
  return arrays;
}

// The frame as the history reads it: its spans one after the other, box k of the frame being
// box k - first_box[s] of span s.
class FrameReader {
 public:
  // ioFirstBoxes: the history's, so that a frame allocates nothing once its span count is seen.
  FrameReader(const BoxFrame& inFrame, std::vector<std::size_t>& ioFirstBoxes)
      : frame_(inFrame), filtered_(inFrame.hasFilters()), first_box_(ioFirstBoxes) {
    first_box_.clear();
    std::size_t first_box = 0;
    for (std::size_t s = 0; s < inFrame.spanCount(); ++s) {
      first_box_.push_back(first_box);
      first_box += inFrame.span(s).count;
    }
    size_ = first_box;
  }
  std::size_t size() const { return size_; }
  bool filtered() const { return filtered_; }

  // Reads frame boxes [inBegin, inEnd) into outBlock and checks them on the way: false when
  // some box has a NaN bound or min > max (`low <= high` is false exactly then, as in
  // validate()). Ids are read as the span numbers them; one beyond 32 bits makes the block
  // unusable too (the full check names it).
  bool read(std::size_t inBegin, std::size_t inEnd, RecordBlock& outBlock) const {
    bool usable = true;
    std::size_t s = spanOf(inBegin);
    for (std::size_t k = inBegin; k < inEnd; ++s) {
      const BoxSpan& span = frame_.span(s);
      const std::size_t first = first_box_[s];
      const std::size_t end = std::min(inEnd, first + span.count);
      for (; k < end; ++k) {
        const std::size_t i = k - first, slot = k - inBegin;
        const double* record = span.bounds + kBoundsPerBox * i;
        for (int array = 0; array < 6; ++array) outBlock.bounds[array][slot] = record[array];
        for (int axis = 0; axis < 3; ++axis) usable &= record[axis] <= record[3 + axis];
        const uint64_t id = span.idOf(i);
        usable &= id <= UINT32_MAX;
        outBlock.ids[slot] = static_cast<uint32_t>(id);
        if (filtered_) {
          outBlock.groups[slot] = span.groupOf(i);
          outBlock.masks[slot] = span.maskOf(i);
        }
      }
    }
    return usable;
  }

 private:
  // The span that holds frame box inBox (the last span that starts at or before it, skipping
  // empty spans).
  std::size_t spanOf(std::size_t inBox) const {
    const auto after = std::upper_bound(first_box_.begin(), first_box_.end(), inBox);
    std::size_t s = static_cast<std::size_t>(after - first_box_.begin()) - 1;
    while (frame_.span(s).count == 0) ++s;
    return s;
  }

  const BoxFrame& frame_;
  const bool filtered_;
  std::vector<std::size_t>& first_box_;  // the first frame box of each span
  std::size_t size_ = 0;
};

// Clears outUnchanged[k] of boxes whose group or mask changed; returns how many did.
std::size_t markFilterChanges(const RecordBlock& inBlock, const BoxColumns& inLast,
                              std::size_t inBegin, std::size_t inEnd, uint8_t* ioUnchanged) {
  std::size_t changed = 0;
  for (std::size_t k = inBegin; k < inEnd; ++k) {
    const bool same_filter = inBlock.groups[k - inBegin] == inLast.groups[k] &&
                             inBlock.masks[k - inBegin] == inLast.masks[k];
    ioUnchanged[k] &= same_filter;
    changed += !same_filter;
  }
  return changed;
}

void copyBlock(const RecordBlock& inBlock, bool inFiltered, std::size_t inBegin,
               std::size_t inCount, BoxColumns& ioLast) {
  for (int axis = 0; axis < 3; ++axis) {
    std::copy(inBlock.bounds[axis], inBlock.bounds[axis] + inCount,
              ioLast.lo[axis].begin() + inBegin);
    std::copy(inBlock.bounds[3 + axis], inBlock.bounds[3 + axis] + inCount,
              ioLast.hi[axis].begin() + inBegin);
  }
  if (!inFiltered) return;
  std::copy(inBlock.groups, inBlock.groups + inCount, ioLast.groups.begin() + inBegin);
  std::copy(inBlock.masks, inBlock.masks + inCount, ioLast.masks.begin() + inBegin);
}

// One pass over the boxes in work units (work_units.h), block by block: a block is read from
// the caller's records into the thread's scratch (checked on the way), compared with ioLast's
// without a branch and, where some box of it differs, copied at once while both are in the
// cache (a separate copy after the sweep would read both frames from memory again; copying a
// whole block keeps the copy a plain streaming one, and unchanged boxes in it are rewritten
// with their own bits). The ids are copied too, so that ioLast equals the frame in every case.
// ioLast has the frame's size, and groups and masks where the frame has them.
FramePass compareAndCopyBlocks(const FrameReader& inFrame, BoxColumns& ioLast,
                               std::vector<uint8_t>& outUnchanged) {
  const std::size_t n = inFrame.size();
  outUnchanged.resize(n);
  const UnitChanges changes = reduceOverItems(
      WorkUnits{n}, UnitChanges{},
      [&](std::size_t inBegin, std::size_t inEnd) {
        UnitChanges unit;
        RecordBlock block;
        for (std::size_t begin = inBegin; begin < inEnd; begin += kBlock) {
          const std::size_t end = std::min(inEnd, begin + kBlock), count = end - begin;
          unit.unusable += !inFrame.read(begin, end, block);
          if (!std::equal(block.ids, block.ids + count, ioLast.ids.begin() + begin)) {
            std::copy(block.ids, block.ids + count, ioLast.ids.begin() + begin);
            ++unit.other_ids;
          }
          const BlockChanges bounds = compareBounds(boundArrays(block), boundArrays(ioLast, begin),
                                                    count, outUnchanged.data() + begin);
          const std::size_t filters =
              inFrame.filtered() ? markFilterChanges(block, ioLast, begin, end, outUnchanged.data())
                                 : 0;
          if (bounds.changed_boxes > 0 || filters > 0) {
            copyBlock(block, inFrame.filtered(), begin, count, ioLast);
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

const FrameDelta& FrameHistory::load(const BoxFrame& inFrame,
                                     std::optional<ValidationError>& outProblem) {
  const FrameReader reader(inFrame, span_first_boxes_);
  const bool had_last = valid_;
  delta_ = FrameDelta();
  valid_ = false;  // from here until remember(), last_ is being made this frame
  const bool comparable =
      had_last && last_.size() == reader.size() && last_.hasFilters() == reader.filtered();
  if (!comparable) {
    // A first frame, or other ids: every box copied, then checked in full.
    copyFrame(inFrame, last_);
    outProblem = checkColumns(last_, inFrame);
    if (had_last) delta_.relation = FrameRelation::kOtherIds;
  } else {
    const FramePass pass = compareAndCopyBlocks(reader, last_, unchanged_);
    // Same ids as a frame that passed: no id can repeat, and only a box found unusable on the
    // way needs the full check (which names the lowest bad box with validate()'s words).
    outProblem = pass.other_ids || pass.unusable ? checkColumns(last_, inFrame) : std::nullopt;
    describeSameSize(pass);
  }
  if (outProblem) forget();
  SAP_ASSERT(outProblem || last_.size() == reader.size(), "the loaded frame lost boxes");
  SAP_ASSERT(delta_.moved_boxes <= reader.size(), "more boxes moved than the frame holds");
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

void FrameHistory::remember() {
  valid_ = true;
}

void FrameHistory::forget() {
  valid_ = false;
  delta_ = FrameDelta();
}

std::size_t FrameHistory::bytesHeld() const {
  std::size_t bytes = last_.ids.capacity() * sizeof(uint32_t) +
                      (last_.groups.capacity() + last_.masks.capacity()) * sizeof(uint32_t) +
                      unchanged_.capacity() + span_first_boxes_.capacity() * sizeof(std::size_t);
  for (int axis = 0; axis < 3; ++axis)
    bytes += (last_.lo[axis].capacity() + last_.hi[axis].capacity()) * sizeof(double);
  return bytes;
}

void FrameHistory::shrinkToFit() {
  last_ = BoxColumns(last_);  // a copy holds only what is used
  unchanged_.shrink_to_fit();
}

}  // namespace sap_broadphase
