// The small-frame path: no state kept between frames; its passes run a unit at a time on the
// threads the frame's plan gave it (work_units.h).
//
// Below a few thousand boxes the bi-dimensional sweep's fixed costs (two endpoint sorts, the
// candidate ranges of Algorithm 1, SuccTrees sized to n) outweigh what it saves. A plain
// sort-and-sweep then wins: sort the boxes by low end on the sweep axis, lay them into the
// cells of a grid over the two other axes, and test each box against the boxes of its cells
// that start before it ends, several candidates at a time.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/frame/box_columns.h"
#include "core/frame/pair_sort.h"
#include "core/runner/buffers.h"
#include "core/sweep/axis_spread.h"

namespace sap_broadphase {

/// Buffers of pairSmallFrame, reused from frame to frame (grown, never shrunk; growth does not
/// zero them).
struct SmallFrameWorkspace {
  Buffer<uint64_t> order;    ///< (low key << 32 | box) on the sweep axis, then sorted
  Buffer<uint64_t> scratch;  ///< the radix sort's second buffer
  /// Float32 bounds rounded outward (sort_keys.h) relative to the frame's key origin
  /// (key_origin.h), six per box in input order: low and high on the sweep axis, then on the
  /// two grid axes.
  Buffer<float> bounds;
  /// The grid's cells one after the other, each a run of its boxes sorted by low key on the
  /// sweep axis (a box reaching several cells is in each), structure of arrays of the bounds
  /// with axis 0 the sweep axis. Each run is followed by kBlock NaNs, so a block of candidates
  /// may read past its last box: NaN compares false, so padding never overlaps anything.
  /// A run's bounds are copied in by the worker that sweeps it, just before its sweep.
  Buffer<float> lo[3];
  Buffer<float> hi[3];
  Buffer<uint32_t> box_of;      ///< box index of each entry of a run
  Buffer<uint32_t> cell_start;  ///< first entry of each cell's run, then the total
  Buffer<uint32_t> cell_range;  ///< the cells each box reaches (packed, input order)
  /// [unit of the sorted boxes][cell]: entries the unit adds to the cell, then the unit's next
  /// entry there while filling.
  Buffer<uint32_t> unit_cell_count;
  std::vector<uint32_t> unit_first_cell;     ///< the sweep's units: first cell of each, then all
  std::vector<PairChunks> pairs_per_worker;  ///< the sweep's pairs, one list per worker
  PairSortScratch pair_scratch;
  /// Most pairs the sweep of the cells may find (BroadphaseConfig::max_pairs): past it the
  /// workers throw TooManyPairs.
  std::size_t max_pairs = SIZE_MAX;
  uint32_t grid_cells = 1;  ///< cells of the last frame's grid (1: one sweep of all boxes)

  /// Bytes held (capacities): for the memory experiment (bench/exp_memory.cpp).
  std::size_t bytesHeld() const;
};

/// The sweep axis of a small frame: the one whose mean box extent is smallest relative to the
/// span of the finite bounds, i.e. the fewest boxes start inside a box's interval (read from
/// ioSpread, the spread of the frame's boxes, measured on one thread if not yet).
int chooseSmallFrameAxis(FrameSpread& ioSpread);

/// Every overlapping, filter-allowed pair of inBoxes (exactly bruteForcePairs' result), in
/// canonical order, into outPairs (replaced), on the threads of the runner's scope
/// (passThreads(); the same pairs for any count). AVX2 blocks of 8 candidates where the CPU has
/// them, a portable loop otherwise (chosen at run time). ioSpread is the spread of inBoxes: the
/// sweep axis and the key origin are read from it.
void pairSmallFrame(const BoxColumns& inBoxes, FrameSpread& ioSpread, SmallFrameWorkspace& ioWork,
                    PairList& outPairs);
/// The same, measuring the spread of inBoxes itself.
void pairSmallFrame(const BoxColumns& inBoxes, SmallFrameWorkspace& ioWork, PairList& outPairs);

/// The same, forced onto the portable loop (for tests and benchmarks on AVX2 machines).
void pairSmallFramePortable(const BoxColumns& inBoxes, SmallFrameWorkspace& ioWork,
                            PairList& outPairs);

}  // namespace sap_broadphase
