// The small-frame path: one thread, one axis, no state kept between frames.
//
// Below a few thousand boxes the bi-dimensional sweep's fixed costs (two endpoint sorts, the
// candidate ranges of Algorithm 1, SuccTrees sized to n) outweigh what it saves. A plain
// single-axis sort-and-sweep then wins: sort the boxes by low end on the sweep axis, and test
// each box against the boxes that start before it ends, several candidates at a time.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/axis_spread.h"
#include "core/pair_sort.h"
#include "sap_broadphase/core/box_set.h"

namespace sap_broadphase {

/// Buffers of pairSmallFrame, reused from frame to frame (grown, never shrunk).
struct SmallFrameWorkspace {
  std::vector<uint64_t> order;    ///< (low key << 32 | box) on the sweep axis, then sorted
  std::vector<uint64_t> scratch;  ///< the radix sort's second buffer
  /// Float32 bounds rounded outward (sort_keys.h) relative to the frame's key origin
  /// (key_origin.h), in sweep order, structure of arrays: axis
  /// 0 is the sweep axis. Low arrays are padded with NaN so a block of candidates may read
  /// past the last box: NaN compares false, so padding never overlaps anything.
  std::vector<float> lo[3];
  std::vector<float> hi[3];
  std::vector<uint32_t> box_of;  ///< box index of each sweep position
  PairSortScratch pair_scratch;
};

/// The sweep axis of a small frame: the one whose mean box extent is smallest relative to the
/// span of the finite bounds, i.e. the fewest boxes start inside a box's interval (read from
/// ioSpread, the spread of the frame's boxes, measured on one thread if not yet).
int chooseSmallFrameAxis(FrameSpread& ioSpread);

/// Every overlapping, filter-allowed pair of inBoxes (exactly bruteForcePairs' result), in
/// canonical order, into outPairs (replaced). One thread; AVX2 blocks of 8 candidates where
/// the CPU has them, a portable loop otherwise (chosen at run time). ioSpread is the spread of
/// inBoxes: the sweep axis and the key origin are read from it.
void pairSmallFrame(const BoxSet& inBoxes, FrameSpread& ioSpread, SmallFrameWorkspace& ioWork,
                    PairList& outPairs);
/// The same, measuring the spread of inBoxes itself.
void pairSmallFrame(const BoxSet& inBoxes, SmallFrameWorkspace& ioWork, PairList& outPairs);

/// The same, forced onto the portable loop (for tests and benchmarks on AVX2 machines).
void pairSmallFramePortable(const BoxSet& inBoxes, SmallFrameWorkspace& ioWork, PairList& outPairs);

}  // namespace sap_broadphase
